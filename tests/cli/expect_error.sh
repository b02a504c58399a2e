#!/usr/bin/env bash
# expect_error.sh REGEX CMD ARGS...: passes when CMD exits 1 (not a crash) with exactly one line on
# stderr starting "lightpass: error:" and matching REGEX, and leaves no temporary files behind.
regex="$1"; shift
err=$("$@" 2>&1 >/dev/null); code=$?
lines=$(printf '%s\n' "$err" | grep -c "lightpass: error:")
if [ "$code" -ne 1 ]; then echo "exit code $code (want 1): $err"; exit 1; fi
if [ "$lines" -ne 1 ]; then echo "want exactly one error line, got: $err"; exit 1; fi
if ! printf '%s\n' "$err" | grep -Eq -- "$regex"; then echo "error does not match '$regex': $err"; exit 1; fi
echo "ok: $err"
