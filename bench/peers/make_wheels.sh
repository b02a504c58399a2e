#!/usr/bin/env bash
# Fills the folder that carries the Filament peer to the GPU machine beside the lightpass bundle:
#   bench/peers/make_wheels.sh OUTDIR [--python PREFIX]   (e.g. OUTDIR = gpu-bundle/peers-wheels)
#   OUTDIR/*.whl         filly (Filament, cp312-abi3) and its dependency numpy, for CPython 3.12 manylinux x86_64
#   OUTDIR/lib/          the shared libraries filly's native module loads that a bare machine lacks
#                        (libX11 and its xcb chain), as tools' bundle-exe copies them for lightpass
#   OUTDIR/lib-glvnd/    libGL.so.1 and what it loads (glvnd's vendor-neutral dispatch): used only where
#                        the GPU machine cannot load its own libGL.so.1 (bench/peers/run.sh checks)
#   OUTDIR/python/       with --python PREFIX (an installed CPython 3.12, e.g. a pyenv version): its
#                        interpreter, stripped libpython and standard library (no tests, IDLE, Tk, SSL),
#                        for a GPU machine without Python >= 3.12 (about 35 MB more); run.sh uses it
#                        only when no python3.12+ is on PATH
# Needs pip (any Python) and, for the libraries, unzip-free Python zipfile and ldd. Existing wheels in
# OUTDIR (or in PEERS_WHEEL_CACHE, e.g. /tmp/whl) are reused.
set -euo pipefail
out=$1
python_prefix=""
if [ "${2:-}" = "--python" ]; then python_prefix=${3:?--python needs the prefix of a CPython 3.12 install}; fi
mkdir -p "$out/lib" "$out/lib-glvnd"
pip_download() {  # the ordinary pip client: binary wheels for the GPU machine's Python 3.12
  python3 -m pip download "$@" --no-deps --only-binary=:all: --python-version 3.12 \
    --platform manylinux_2_28_x86_64 --platform manylinux_2_27_x86_64 --platform manylinux_2_17_x86_64 \
    --platform manylinux2014_x86_64 -d "$out" -q
}
for pkg in filly numpy; do
  if ls "$out"/$pkg-*.whl >/dev/null 2>&1; then continue; fi
  if [ -n "${PEERS_WHEEL_CACHE:-}" ] && ls "$PEERS_WHEEL_CACHE"/$pkg-*.whl >/dev/null 2>&1; then
    cp "$PEERS_WHEEL_CACHE"/$pkg-*.whl "$out/"
  else
    pip_download "$pkg"
  fi
done
wheel=$(ls "$out"/filly-*.whl | head -1)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
python3 -m zipfile -e "$wheel" "$tmp"
native=$(ls "$tmp"/filly/_native*.so | head -1)
ldd "$native" | awk '/=> \// {print $3}' | while read -r lib; do
  case "$(basename "$lib")" in
    libc.so*|libm.so*|libpthread.so*|libdl.so*|librt.so*|ld-linux*|libstdc++.so*|libgcc_s.so*) ;;
    libcuda.so*|libnvidia*|libEGL*.so*|libOpenGL.so*) ;;  # the driver's; EGL is loaded at run time
    libGL.so*|libGLX.so*|libGLdispatch.so*) cp -L "$lib" "$out/lib-glvnd/" ;;
    *) cp -L "$lib" "$out/lib/" ;;
  esac
done
if [ -n "$python_prefix" ]; then
  exe=$python_prefix/bin/python3.12
  [ -x "$exe" ] || { echo "make_wheels.sh: $exe: not an executable CPython 3.12" >&2; exit 1; }
  rm -rf "$out/python" && mkdir -p "$out/python/bin" "$out/python/lib"
  cp -L "$exe" "$out/python/bin/python3.12"
  if ls "$python_prefix"/lib/libpython3.12.so.1.0 >/dev/null 2>&1; then
    cp -L "$python_prefix/lib/libpython3.12.so.1.0" "$out/python/lib/"
    strip --strip-unneeded "$out/python/lib/libpython3.12.so.1.0" 2>/dev/null || true
  fi
  (cd "$python_prefix/lib" && tar cf - --exclude=test --exclude=tests --exclude=__pycache__ --exclude=idlelib \
     --exclude=tkinter --exclude=turtledemo --exclude=ensurepip --exclude='config-3.12*' --exclude=site-packages \
     --exclude='_tkinter*' --exclude='_ssl*' --exclude='_hashlib*' --exclude='_curses*' --exclude='readline*' \
     --exclude='_dbm*' --exclude='_gdbm*' --exclude='nis*' --exclude='_crypt*' --exclude='_test*' --exclude='xx*' \
     python3.12) | (cd "$out/python/lib" && tar xf -)
  mkdir -p "$out/python/lib/python3.12/site-packages"
  # What the interpreter and its extension modules load beyond the C runtime (libffi for ctypes, ...).
  for so in "$out/python/bin/python3.12" "$out"/python/lib/python3.12/lib-dynload/*.so; do
    ldd "$so" 2>/dev/null | awk '/=> \// {print $3}'
  done | sort -u | while read -r lib; do
    case "$(basename "$lib")" in
      libc.so*|libm.so*|libpthread.so*|libdl.so*|librt.so*|ld-linux*|libstdc++.so*|libgcc_s.so*|libpython3*) ;;
      *) cp -L "$lib" "$out/python/lib/" ;;
    esac
  done
fi
echo "peers wheels in $out: $(cd "$out" && ls *.whl | tr '\n' ' ')"
echo "  lib: $(ls "$out/lib" | tr '\n' ' ')"
echo "  lib-glvnd: $(ls "$out/lib-glvnd" | tr '\n' ' ')"
[ -d "$out/python" ] && echo "  python: $("$out/python/bin/python3.12" --version 2>&1 || true) ($(du -sh "$out/python" | cut -f1))"
du -sh "$out" | cut -f1
