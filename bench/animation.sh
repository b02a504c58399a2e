#!/bin/bash
# What playing glTF animation costs per frame, at 60 fps from t = 1 s, 1080p and 4K, still
# (--animation none) and playing (its first clip), with motion blur on so the G-buffer writes velocity
# (the previous positions are read), on two models of about 102,400 vertices:
#   grid:    16 nodes that all move (scripts/make_animated_grid.py): node animation;
#   skinned: one mesh skinned to 8 joints that all bend, with 2 animated morph targets
#            (scripts/make_skinned_grid.py): every vertex morphed and skinned every frame.
# Playing, posed both ways (--skinning gpu: the skinning compute pass, the default; --skinning cpu:
# posed on the CPU and uploaded, the reference). Reports the passes' GPU ms (the `skinning` pass's
# own row with gpu), the CPU ms of SceneGpu::pose (`animation pose: CPU median`, `animation_pose_ms`
# in the JSON: with gpu only node matrices, joint matrices and the pose upload) and the CPU frame
# (submit) ms. From the repository root:
#   bench/animation.sh BUNDLE OUTDIR    (BUNDLE: run, gl_tests, lib/); OUTDIR/skinning.md: the table
#   (bench/summarize_skinning.py)
set -u
B=$(cd "$1" && pwd); R=$2; mkdir -p $R
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $R/device.txt
LD_LIBRARY_PATH=$B/lib $B/gl_tests --gtest_brief=1 --gtest_filter='AnimationGl*:GpuSkinning*' > $R/gl_tests_animation.txt 2>&1
tail -3 $R/gl_tests_animation.txt
python3 scripts/make_animated_grid.py $R/grid.gltf 102400 | tee $R/model.txt
python3 scripts/make_skinned_grid.py $R/skinned.gltf 102400 | tee -a $R/model.txt
for model in grid skinned; do
  for size in 1920x1080 3840x2160; do
    for variant in none:gpu 0:gpu 0:cpu; do
      animation=${variant%:*}; skinning=${variant#*:}; tag=${model}_${size}_${animation}_$skinning
      echo "== $model $size --animation $animation --skinning $skinning" | tee -a $R/animation.txt
      $B/run render --model $R/$model.gltf --size $size --time 1 --fps 60 --frames 200 --warmup 20 --motion-blur \
        --animation $animation --skinning $skinning --out $R/$tag.png --timings-json $R/$tag.json \
        | tee -a $R/animation.txt
    done
  done
done
python3 bench/summarize_skinning.py $R
