#!/usr/bin/env bash
# On the GPU machine: vkstats over every .vk/NAME.spv (with .vk/NAME.bindings), a line of registers a
# program. IR="a b": also the driver's internal representations of .vk/a.spv and .vk/b.spv. Call with
# carry [".gl", ".vk"] (tools/shader-stats/README.md). Writes $OUT/vkstats.txt.
set -uo pipefail
shopt -s nullglob
for f in .gl/*.deb; do dpkg -x "$f" /; done
ldconfig
# NVIDIA's ICD, wherever the machine has it, and the libraries it opens (/usr/local/nvidia/lib64 there).
for icd in /usr/share/vulkan/icd.d/nvidia_icd.json /usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json; do
  [ -f "$icd" ] && export VK_DRIVER_FILES=$icd && break
done
export LD_LIBRARY_PATH=/usr/local/nvidia/lib64:/usr/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader
for spv in .vk/*.spv; do
  name=${spv%.spv}
  ir=()
  # The driver's internal representations of the programs named in IR (at most a few come back).
  [[ " ${IR:-} " == *" $(basename "$name") "* ]] && ir=("${OUT:-/tmp}/$(basename "$name").ir")
  .vk/vkstats "$spv" "$name.bindings" "${ir[@]}" 2>&1
done | tee "${OUT:-/tmp}/vkstats.txt"
