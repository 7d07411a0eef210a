# The built-in scenes: every scene file in assets/scenes/ (the presets) and assets/scenes/stress/
# (the stress scenes), built into the binary as the SRTM tile is. A C++ file of one .incbin a scene
# is written at configure time into `out_dir`; a scene file added or removed reconfigures.
function(scour_builtin_scenes root out_dir out_var)
  file(GLOB presets CONFIGURE_DEPENDS ${root}/assets/scenes/*.json)
  file(GLOB stress CONFIGURE_DEPENDS ${root}/assets/scenes/stress/*.json)
  set(asm "")
  set(table "")
  set(index 0)
  foreach(path ${presets} ${stress})
    file(RELATIVE_PATH rel ${root}/assets/scenes ${path})
    string(APPEND asm "    \"scour_scene_${index}_begin:\\n\"\n    \".incbin \\\"${path}\\\"\\n\"\n    \"scour_scene_${index}_end:\\n\"\n")
    string(APPEND table "extern \"C\" const unsigned char scour_scene_${index}_begin[], scour_scene_${index}_end[];\n")
    list(APPEND entries "{\"${rel}\", scour_scene_${index}_begin, size_t(scour_scene_${index}_end - scour_scene_${index}_begin)}")
    math(EXPR index "${index} + 1")
  endforeach()
  list(JOIN entries ",\n      " entries)
  file(CONFIGURE OUTPUT ${out_dir}/builtin_scene_files.cpp CONTENT
"// Written by src/scene/builtin_scenes.cmake from assets/scenes/: do not edit.
#include \"scene/assets.h\"

asm(\".section .rodata\\n\"
${asm}    \".previous\\n\");

${table}
namespace scour {

const std::vector<Asset>& builtinSceneFiles() {
  static const std::vector<Asset> files = {
      ${entries}};
  return files;
}

}  // namespace scour
" @ONLY)
  set(${out_var} ${out_dir}/builtin_scene_files.cpp PARENT_SCOPE)
  set_source_files_properties(${out_dir}/builtin_scene_files.cpp PROPERTIES OBJECT_DEPENDS "${presets};${stress}")
endfunction()
