#!/usr/bin/env bash
# Path-traced ground truth for lightpass's IBL: makes a Python environment with Mitsuba 3 and numpy
# (once; $MITSUBA_VENV, default ../venv-mitsuba beside the repository) and runs ground_truth.py with
# the arguments given, e.g.
#   bench/mitsuba/run.sh --size 256x144 --spp 256
#   bench/mitsuba/run.sh --maps hdr/sky.exr --spp 64
#   bench/mitsuba/run.sh principled --spp 128   (metallic-roughness spheres vs Mitsuba's principled: principled.py)
#   bench/mitsuba/run.sh cornell --size 256x256 --spp 512   (the IBL-lit Cornell box, AO off / on: cornell_ao.py)
#   bench/mitsuba/run.sh tracer --spp 256 [--bounces 4]     (lightpass's path tracer vs Mitsuba: tracer_check.py)
# lightpass must be built (build/app/lightpass, or --lightpass PATH).
set -euo pipefail
repo="$(cd "$(dirname "$0")/../.." && pwd)"
venv="${MITSUBA_VENV:-$repo/../venv-mitsuba}"
if [ ! -x "$venv/bin/python" ] || ! "$venv/bin/python" -c 'import mitsuba, numpy' 2>/dev/null; then
    echo "bench/mitsuba/run.sh: making $venv (mitsuba, numpy)" >&2
    python3 -m venv "$venv"
    "$venv/bin/pip" install --quiet mitsuba numpy
fi
cd "$repo"
if [ "${1:-}" = cornell ]; then
    shift
    exec "$venv/bin/python" bench/mitsuba/cornell_ao.py "$@"
fi
if [ "${1:-}" = tracer ]; then
    shift
    exec "$venv/bin/python" bench/mitsuba/tracer_check.py "$@"
fi
if [ "${1:-}" = principled ]; then
    shift
    exec "$venv/bin/python" bench/mitsuba/principled.py "$@"
fi
exec "$venv/bin/python" bench/mitsuba/ground_truth.py "$@"
