#!/usr/bin/env bash
# scripts/setup and scripts/setup-tools with every package missing, against stand-ins for dpkg-query,
# id, apt-get and sudo (nothing is installed): as root apt-get runs without sudo (a Debian without
# sudo); not root and no sudo is one line saying so; not root with sudo goes through sudo.
#   setup_root_or_sudo.sh SOURCE_DIR
set -euo pipefail
src=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
mkdir "$dir/bin"
ln -s "$(command -v grep)" "$dir/bin/grep"
printf '#!/bin/sh\nexit 1\n' >"$dir/bin/dpkg-query"
printf '#!/bin/sh\necho "${FAKE_UID:?}"\n' >"$dir/bin/id"
printf '#!/bin/sh\necho "apt-get $*" >>"$LOG"\n' >"$dir/bin/apt-get"
chmod +x "$dir/bin/"*
bash=$(command -v bash)
run() { LOG="$dir/log" PATH="$dir/bin" "$bash" "$@"; }
fail() { echo "$1"; [ -f "$dir/log" ] && cat "$dir/log"; exit 1; }

: >"$dir/log"
FAKE_UID=0 run "$src/scripts/setup" >/dev/null 2>&1 || fail "setup as root without sudo failed"
grep -q "^apt-get install .*build-essential" "$dir/log" || fail "setup as root did not run apt-get install"

: >"$dir/log"
for script in setup setup-tools; do
  if err=$(FAKE_UID=1000 run "$src/scripts/$script" 2>&1 >/dev/null); then fail "$script without root or sudo succeeded"; fi
  grep -q "^$script: installing .* needs root: run it as root, or install sudo$" <<<"$err" || fail "$script said: $err"
done
[ -s "$dir/log" ] && fail "apt-get ran without root"

printf '#!/bin/sh\necho "sudo $*" >>"$LOG"\nexec "$@"\n' >"$dir/bin/sudo"
chmod +x "$dir/bin/sudo"
FAKE_UID=1000 run "$src/scripts/setup" >/dev/null 2>&1 || fail "setup with sudo failed"
grep -q "^sudo apt-get install .*build-essential" "$dir/log" || fail "setup as a user did not use sudo"
echo "setup: root runs apt-get directly, a user without sudo gets one line, a user with sudo uses it"
