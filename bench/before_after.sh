#!/bin/bash
# Before/after on the GPU, one process per run, interleaved base, new, base, new so drift shows as the
# difference between rounds. Run from the repository root on the GPU machine:
#   bench/before_after.sh BUNDLE OUTDIR
# BUNDLE holds run (the new lightpass), run-base (the old one, same libraries), gl_tests and
# cuda_tests and lib/; gl_tests run with the per-pass GL state check (LIGHTPASS_GL_STATE_CHECKS=1). The gallery needs ../shared/assets.
# Tables: bench/compare_runs.py OUTDIR frame_cornell frame_gallery post lights.
set -u
B=$(cd "$1" && pwd); R=$2; mkdir -p $R
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $R/device.txt
LIGHTPASS_GL_STATE_CHECKS=1 LD_LIBRARY_PATH=$B/lib $B/gl_tests --gtest_brief=1 > $R/gl_tests.txt 2>&1; tail -4 $R/gl_tests.txt
LD_LIBRARY_PATH=$B/lib $B/cuda_tests > $R/cuda_tests.txt 2>&1; tail -3 $R/cuda_tests.txt
$B/run graph --scene scenes/cornell.json --bloom --toon --post-backend cuda > $R/graph_cuda.txt 2>&1
for round in 1 2; do for v in base new; do
  LP=$B/run; [ $v = base ] && LP=$B/run-base
  o=$R/$v$round; mkdir -p $o
  for s in cornell gallery; do
    $LP bench --scene scenes/$s.json --frames 200 --warmup 30 --floors --vary '--size 1920x1080,3840x2160' \
      --timings-json $o/frame_$s.json -q > $o/frame_$s.log 2>&1
  done
  $LP bench --scene scenes/cornell.json --frames 100 --floors --bloom --toon \
    --vary '--post-backend glsl|--post-backend glsl --bloom-method mip-chain|--post-backend cuda|--post-backend cuda --bloom-method mip-chain' \
    --vary '--size 1920x1080,3840x2160' --timings-json $o/post.json -q > $o/post.log 2>&1
  $LP bench --scene scenes/gallery.json --size 1920x1080 --frames 100 --floors \
    --vary '--local-lights fullscreen,scissor,volumes,tiled' --timings-json $o/lights.json -q > $o/lights.log 2>&1
  if [ $round = 1 ]; then
    $LP sweep --scene scenes/cornell.json --size 1920x1080 --frames 100 --knob shadow-size --knob render-scale \
      --out-dir $o/sweep -q > $o/sweep.log 2>&1
    for s in cornell gallery; do
      $LP render --scene scenes/$s.json --size 960x540 --bloom --toon --out $o/$s.png --exr $o/$s.exr -q > /dev/null 2>&1
      $LP render --scene scenes/$s.json --size 960x540 --local-lights volumes --out $o/${s}_volumes.png -q > /dev/null 2>&1
    done
  fi
  echo "round $round $v done"
done; done
for f in cornell.png cornell.exr gallery.png gallery.exr cornell_volumes.png gallery_volumes.png; do
  cmp -s $R/base1/$f $R/new1/$f && echo "$f identical" || echo "$f DIFFERS"
done | tee $R/images.txt
python3 - "$R" <<'PY' >> $R/images.txt 2>&1
import sys; from PIL import Image; import numpy as np
R = sys.argv[1]
for f in ["cornell.png","gallery.png","cornell_volumes.png","gallery_volumes.png"]:
    a=np.asarray(Image.open(R+"/base1/"+f)).astype(int); b=np.asarray(Image.open(R+"/new1/"+f)).astype(int)
    print(f, "max |diff|", abs(a-b).max(), "pixels differing", int((abs(a-b).max(axis=2)>0).sum()))
PY
cat $R/images.txt
