#!/usr/bin/env bash
# SPIR-V of a raycaster program and variants of it, for vkstats on the GPU machine.
#   make_variants.sh SOURCE OUTDIR NAME=DEFINES [NAME=DEFINES ...]
# SOURCE: the program's whole GLSL as the renderer compiles it (FCCVDB_DUMP_SHADERS=DIR fccvdb render
# ... writes it); DEFINES: the measurement knobs, "A=1;B=2" as in FCCVDB_SHADER_DEFINES ("" for none).
# Writes OUTDIR/NAME.spv and OUTDIR/NAME.bindings. Needs glslang-tools and spirv-cross (Debian).
set -euo pipefail
src=$1 out=$2
shift 2
mkdir -p "$out"
here=$(cd "$(dirname "$0")" && pwd)
for spec in "$@"; do
  name=${spec%%=*} defs=${spec#*=}
  defines=""
  IFS=';' read -ra items <<<"$defs"
  for item in "${items[@]}"; do
    [ -z "$item" ] && continue
    if [[ $item == *=* ]]; then defines+="#define ${item%%=*} ${item#*=}\n"; else defines+="#define $item 1\n"; fi
  done
  # After the #version line, as the renderer's withDefines puts them.
  { head -1 "$src"; printf '%b' "$defines"; tail -n +2 "$src"; } >"$out/$name.comp"
  # -R: OpenGL's loose uniforms into a default uniform block; GL's separate binding spaces kept apart.
  glslangValidator -V --target-env vulkan1.2 -R --amb --aml --sib 100 --stb 300 --sub 400 -S comp \
    -o "$out/$name.spv" "$out/$name.comp" >"$out/$name.log" || { cat "$out/$name.log"; exit 1; }
  spirv-cross "$out/$name.spv" --reflect | python3 "$here/bindings.py" >"$out/$name.bindings"
  rm -f "$out/$name.comp" "$out/$name.log"
done
