# sdk_install_test.cmake -- the installed SDK builds an out-of-tree plugin.
#
#   cmake -DBUILD_DIR=<acetate build> -DSOURCE_DIR=<acetate source> -DWORK_DIR=<scratch dir>
#         [-DLIBDIR=lib] [-DCXX_COMPILER=<c++>] [-DGENERATOR=<generator>] [-DNM=<nm>]
#         [-DRENDER=OFF]
#         -P tests/e2e/sdk_install_test.cmake
#
# 1. cmake --install <BUILD_DIR> --prefix <WORK_DIR>/prefix, and checks the installed tree
#    (CLI, headers, CMake package) and that the installed `acetate` runs (`--help`).
#    The installed programs default to the user's registry ($XDG_DATA_HOME/acetate, else
#    ~/.local/share/acetate), never the build tree's, and import the installed sign-offs:
#    installed acetate-harness validates the installed lighting plugin into that registry, and
#    installed acetate then loads it (and refuses it with an empty registry). Installed bless
#    without --references is refused in one line and writes nothing into the installation.
#    examples/embedding-host, built against the installed package (Acetate::host), refuses the
#    plugin with the same line as acetate, renders with it once validated, and renders the
#    harbour floor by floor (--allow-unvalidated), no frame allocating or compiling.
# 2. Copies examples/out-of-tree-plugin to <WORK_DIR>/src, configures it in <WORK_DIR>/build
#    with CMAKE_PREFIX_PATH=<WORK_DIR>/prefix (and checks find_package found that prefix), and
#    builds it; the build checks each plugin's shaders with the installed `acetate`.
# 3. Checks each plugin the example builds (tint.so, drop_shadow.so, colour_grade.so): its
#    dynamic symbol table defines acetate_effect_entry_v1 and nothing else but the linker's
#    standard symbols; it needs no Acetate library; its generated header embeds each shader;
#    it carries the source digest acetate_add_effect() computes from its sources and shaders.
# 4. Renders examples/out-of-tree-plugin/scene.json with the installed CLI and the plugins
#    (validation layers on; every plugin loaded; no premultiplied violations; the image
#    differs from the scene without effects). Skipped with -DRENDER=OFF.
# 5. Edits the copy of tint.frag, rebuilds, and checks the embedded-shader header and the
#    digest follow.
# 6. Puts a GLSL error on tint.frag's last line: the build fails naming tint.frag and that
#    line, and fails again on the next build (the check is not skipped once it has failed).
# Any failure ends the script with message(FATAL_ERROR), so ctest reports the test failed.
cmake_minimum_required(VERSION 3.20)

foreach(var BUILD_DIR SOURCE_DIR WORK_DIR)
  if(NOT ${var})
    message(FATAL_ERROR "sdk_install_test: -D${var}=... is required")
  endif()
  cmake_path(ABSOLUTE_PATH ${var} NORMALIZE)
endforeach()
if(NOT LIBDIR)
  set(LIBDIR lib)
endif()
if(NOT NM)
  find_program(NM nm)
  if(NOT NM)
    message(FATAL_ERROR "sdk_install_test: nm not found (pass -DNM=...)")
  endif()
endif()
find_program(READELF readelf)

set(prefix "${WORK_DIR}/prefix")
set(example_src "${WORK_DIR}/src/out-of-tree-plugin")
set(example_build "${WORK_DIR}/build")
# Only these subfolders of WORK_DIR are ever removed.
file(REMOVE_RECURSE "${prefix}" "${WORK_DIR}/src" "${example_build}")
file(MAKE_DIRECTORY "${WORK_DIR}")

# Runs a command; on failure prints its output and fails the test.
function(run_step what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "sdk_install_test: ${what} failed (${rc}):\n  ${ARGN}\n${out}")
  endif()
  message(STATUS "ok: ${what}")
  set(step_output "${out}" PARENT_SCOPE)
endfunction()

# Configures a project copied from examples/ against the installed prefix, with this build's
# generator and compiler.
function(configure_against_prefix what source build)
  set(args -S "${source}" -B "${build}" "-DCMAKE_PREFIX_PATH=${prefix}")
  if(GENERATOR)
    list(APPEND args -G "${GENERATOR}")
  endif()
  if(CXX_COMPILER)
    list(APPEND args "-DCMAKE_CXX_COMPILER=${CXX_COMPILER}")
  endif()
  run_step("configure ${what}" "${CMAKE_COMMAND}" ${args})
endfunction()

function(require_file path)
  if(NOT EXISTS "${path}")
    message(FATAL_ERROR "sdk_install_test: missing ${path}")
  endif()
endfunction()

# The digest acetate_add_effect() defines: SHA-256 over the per-file SHA-256s, in order.
function(expected_digest out_var)
  set(hashes "")
  foreach(file IN LISTS ARGN)
    file(SHA256 "${file}" hash)
    string(APPEND hashes "${hash}")
  endforeach()
  string(SHA256 digest "${hashes}")
  set(${out_var} "${digest}" PARENT_SCOPE)
endfunction()

function(require_digest library digest)
  file(STRINGS "${library}" found REGEX "^[0-9a-f]+$" LENGTH_MINIMUM 64)
  if(NOT digest IN_LIST found)
    message(FATAL_ERROR "sdk_install_test: ${library} does not carry the source digest ${digest}")
  endif()
endfunction()

# ---- 1. Install, and check the installed tree ----
require_file("${BUILD_DIR}/CMakeCache.txt")
run_step("cmake --install" "${CMAKE_COMMAND}" --install "${BUILD_DIR}" --prefix "${prefix}")
foreach(path
    bin/acetate
    include/acetate/effect.h
    include/acetate/effect.hpp
    include/acetate/effect_params.hpp
    include/acetate/version.h
    ${LIBDIR}/cmake/Acetate/AcetateConfig.cmake
    ${LIBDIR}/cmake/Acetate/AcetateConfigVersion.cmake
    ${LIBDIR}/cmake/Acetate/AcetateTargets.cmake
    ${LIBDIR}/cmake/Acetate/AcetateEffect.cmake
    ${LIBDIR}/cmake/Acetate/AcetateEmbedGlsl.cmake
    bin/acetate-harness
    ${LIBDIR}/acetate/harness-neighbours/spread_floor.so
    ${LIBDIR}/acetate/harness-neighbours/spread_global.so
    share/acetate/validation/signoffs.json
    share/acetate/validation/allowed_signers
    share/acetate/validation/revoked_keys
    ${LIBDIR}/acetate/plugins/lighting.so)
  require_file("${prefix}/${path}")
endforeach()
run_step("installed acetate --help" "${prefix}/bin/acetate" --help)

# ---- 1b. Installed programs find the user's registry and the installed sign-offs ----
set(user_env "${CMAKE_COMMAND}" -E env --unset=ACETATE_REGISTRY "HOME=${WORK_DIR}/home")
file(REMOVE_RECURSE "${WORK_DIR}/home" "${WORK_DIR}/xdg-data")
run_step("installed acetate-harness status, XDG_DATA_HOME unset"
  ${user_env} --unset=XDG_DATA_HOME "${prefix}/bin/acetate-harness" status)
if(NOT step_output MATCHES "registry ${WORK_DIR}/home/.local/share/acetate/registry.json \\(sign-offs verified with ${prefix}/share/acetate/validation/allowed_signers\\)\n")
  message(FATAL_ERROR "sdk_install_test: with XDG_DATA_HOME unset, the installed harness does "
                      "not use ~/.local/share/acetate/registry.json:\n${step_output}")
endif()
set(xdg_env ${user_env} "XDG_DATA_HOME=${WORK_DIR}/xdg-data")
set(xdg_registry "${WORK_DIR}/xdg-data/acetate/registry.json")
run_step("installed acetate-harness status" ${xdg_env} "${prefix}/bin/acetate-harness" status)
if(NOT step_output MATCHES "registry ${xdg_registry} ")
  message(FATAL_ERROR "sdk_install_test: the installed harness does not use "
                      "$XDG_DATA_HOME/acetate/registry.json:\n${step_output}")
endif()

# bless from the installation, told nowhere else to write: refused in one line, and the
# installed references are left as they were, byte for byte.
function(digest_of_references out)
  file(GLOB_RECURSE files "${prefix}/share/acetate/validation/references/*")
  set(all "")
  foreach(f IN LISTS files)
    file(SHA256 "${f}" sha)
    string(APPEND all "${f} ${sha}\n")
  endforeach()
  set(${out} "${all}" PARENT_SCOPE)
endfunction()
digest_of_references(references_before)
execute_process(COMMAND ${xdg_env} --unset=ACETATE_REFERENCES "${prefix}/bin/acetate-harness"
  bless "${prefix}/${LIBDIR}/acetate/plugins/lighting.so" --by tester@example.org
  --report "${WORK_DIR}/bless-report"
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
digest_of_references(references_after)
set(expected "acetate-harness: bless: give --references DIR (or $ACETATE_REFERENCES): bless does "
             "not write into this installation's ${prefix}/share/acetate/validation/references;")
string(JOIN "" expected ${expected})
string(FIND "${err}" "${expected}" at)
string(REGEX MATCHALL "\n" lines "${err}")
list(LENGTH lines line_count)
if(rc EQUAL 0 OR NOT at EQUAL 0 OR NOT line_count EQUAL 1
   OR NOT references_before STREQUAL references_after OR references_before STREQUAL "")
  message(FATAL_ERROR "sdk_install_test: installed bless without --references was not refused "
                      "in one line, the installed references untouched (exit ${rc}):\n${out}${err}")
endif()
message(STATUS "ok: installed bless without --references is refused, the installation untouched")

# A one-floor scene that names the installed lighting plugin, with the installed art.
set(art "${prefix}/share/acetate/examples/harbour")
file(WRITE "${WORK_DIR}/lit.json" "{\"format\": \"acetate-scene/1\",
  \"canvas\": {\"width\": 160, \"height\": 90},
  \"floors\": [{\"name\": \"ground\",
    \"tiles\": [{\"image\": \"${art}/ground.png\", \"rect\": [0, 0, 160, 90]}],
    \"lights\": [{\"pos\": [80, 45], \"radius\": 60, \"color\": [1, 0.8, 0.6], \"intensity\": 2}],
    \"effects\": [{\"plugin\": \"acetate.lighting\"}]}]}")
set(render_env ${xdg_env} ACETATE_VALIDATION=1 "MESA_SHADER_CACHE_DIR=${WORK_DIR}/cache/mesa"
  "XDG_CACHE_HOME=${WORK_DIR}/cache/xdg")
file(MAKE_DIRECTORY "${WORK_DIR}/cache/mesa" "${WORK_DIR}/cache/xdg")
execute_process(COMMAND ${render_env} "${prefix}/bin/acetate" render "${WORK_DIR}/lit.json"
  -o "${WORK_DIR}/lit.png" RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
if(rc EQUAL 0 OR NOT out MATCHES "registry ${xdg_registry}")
  message(FATAL_ERROR "sdk_install_test: installed acetate did not refuse the unvalidated "
                      "plugin naming the user's registry (exit ${rc}):\n${out}")
endif()
message(STATUS "ok: installed acetate refuses an unvalidated plugin, naming ${xdg_registry}")
# The refusal without its program's prefix and its last clause (how to load anyway, which each
# program words for its own user): the embedding host must print the same.
string(REGEX MATCH "acetate: ([^\n]*is not VALIDATED[^\n]*); run acetate-harness validate" cli_refusal "${out}")
set(cli_refusal "${CMAKE_MATCH_1}")

# ---- 1c. A program embedding the host, built against the installed package ----
set(embed_src "${WORK_DIR}/src/embedding-host")
set(embed_build "${WORK_DIR}/embedding-build")
file(REMOVE_RECURSE "${embed_build}")
file(COPY "${SOURCE_DIR}/examples/embedding-host" DESTINATION "${WORK_DIR}/src")
configure_against_prefix("the embedding host" "${embed_src}" "${embed_build}")
run_step("build the embedding host" "${CMAKE_COMMAND}" --build "${embed_build}")
set(embedding_host "${embed_build}/embedding-host")
require_file("${embedding_host}")
execute_process(COMMAND ${render_env} "${embedding_host}" "${WORK_DIR}/lit.json"
  "${WORK_DIR}/embedded-refused" RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
string(FIND "${err}" "embedding-host: ${cli_refusal}; run acetate-harness validate" same)
if(rc EQUAL 0 OR cli_refusal STREQUAL "" OR same EQUAL -1 OR EXISTS "${WORK_DIR}/embedded-refused/floor0.png")
  message(FATAL_ERROR "sdk_install_test: the embedding host did not refuse the unvalidated "
                      "plugin as acetate does (exit ${rc}); acetate said:\n  ${cli_refusal}\n"
                      "the embedding host said:\n${err}")
endif()
message(STATUS "ok: the embedding host refuses the unvalidated plugin with acetate's line")
run_step("installed acetate-harness validate lighting.so (installed sign-offs)"
  ${render_env} "${prefix}/bin/acetate-harness" validate "${prefix}/${LIBDIR}/acetate/plugins/lighting.so"
  --report "${WORK_DIR}/lighting-report")
if(NOT step_output MATCHES "share/acetate/validation/signoffs.json")
  message(FATAL_ERROR "sdk_install_test: validate did not import the installed sign-offs:\n${step_output}")
endif()
run_step("installed acetate-harness status after validate" ${xdg_env} "${prefix}/bin/acetate-harness" status)
if(NOT step_output MATCHES "acetate.lighting[^\n]*VALIDATED")
  message(FATAL_ERROR "sdk_install_test: lighting is not VALIDATED in ${xdg_registry}:\n${step_output}")
endif()
run_step("installed acetate renders with the plugin it validated" ${render_env}
  "${prefix}/bin/acetate" render "${WORK_DIR}/lit.json" -o "${WORK_DIR}/lit.png")
require_file("${WORK_DIR}/lit.png")
run_step("the embedding host renders with the plugin validated" ${render_env}
  "${embedding_host}" "${WORK_DIR}/lit.json" "${WORK_DIR}/embedded-lit")
require_file("${WORK_DIR}/embedded-lit/floor0.png")
# The harbour with plugins not validated here: loaded with a warning each, every floor rendered
# in turn, and no frame after the load allocates or compiles anything.
run_step("the embedding host renders the harbour floor by floor (--allow-unvalidated)"
  ${render_env} "${embedding_host}" "${art}/scene.json" "${WORK_DIR}/embedded-harbour"
  --time 2.5 --day-cycle 3 --allow-unvalidated)
foreach(floor 0 1 2 3)
  require_file("${WORK_DIR}/embedded-harbour/floor${floor}.png")
  if(NOT step_output MATCHES "floor ${floor} \\([a-z]+\\): [0-9.]+ ms, [0-9]+ passes, 0 allocations, 0 compiles")
    message(FATAL_ERROR "sdk_install_test: the embedding host's frame of floor ${floor}:\n${step_output}")
  endif()
endforeach()
# The day run live: `day` set on the four lighting entries in place (no reload), and the frames
# after it allocate and compile nothing.
foreach(day "0.00" "0.50" "1.00")
  if(NOT step_output MATCHES "day ${day}: set on 4 effects in [0-9.]+ ms \\(in place\\), frame [0-9.]+ ms, 0 allocations, 0 compiles")
    message(FATAL_ERROR "sdk_install_test: the embedding host's day ${day}:\n${step_output}")
  endif()
endforeach()
if(NOT step_output MATCHES "warning: loading unvalidated plugin acetate.water")
  message(FATAL_ERROR "sdk_install_test: no warning for the unvalidated plugins:\n${step_output}")
endif()
# The camera: a 640x360 window flown over the harbour at scale 1, then zoomed in at 2. Each
# scale's first frame builds the effects for it; every later move and frame allocates and
# compiles nothing.
run_step("the embedding host flies a camera over the harbour (--fly 4)" ${render_env}
  "${embedding_host}" "${art}/scene.json" "${WORK_DIR}/embedded-fly" --fly 4 --allow-unvalidated)
require_file("${WORK_DIR}/embedded-fly/fly-scale100.png")
require_file("${WORK_DIR}/embedded-fly/fly-scale200.png")
foreach(scale "1.00" "2.00")
  string(REGEX MATCHALL "fly scale ${scale} at [^\n]*\(moved\)[^\n]*" moves "${step_output}")
  list(LENGTH moves count)
  if(NOT count EQUAL 3)
    message(FATAL_ERROR "sdk_install_test: 3 moves expected at scale ${scale}:\n${step_output}")
  endif()
  foreach(move IN LISTS moves)
    if(NOT move MATCHES ", 0 allocations, 0 compiles$")
      message(FATAL_ERROR "sdk_install_test: a camera move that cost more than a frame: ${move}")
    endif()
  endforeach()
  if(NOT step_output MATCHES "fly scale ${scale}: 3 frames after the first in [0-9.]+ s, [0-9.]+ frames per second")
    message(FATAL_ERROR "sdk_install_test: no frames per second at scale ${scale}:\n${step_output}")
  endif()
endforeach()

# ---- 2. Build the out-of-tree example against the installed prefix ----
file(COPY "${SOURCE_DIR}/examples/out-of-tree-plugin" DESTINATION "${WORK_DIR}/src")
configure_against_prefix("the out-of-tree plugin" "${example_src}" "${example_build}")
file(STRINGS "${example_build}/CMakeCache.txt" acetate_dir REGEX "^Acetate_DIR:")
string(REGEX REPLACE "^Acetate_DIR:[A-Z]+=" "" acetate_dir "${acetate_dir}")
file(REAL_PATH "${prefix}/${LIBDIR}/cmake/Acetate" want_dir)
if(EXISTS "${acetate_dir}")
  file(REAL_PATH "${acetate_dir}" acetate_dir)
endif()
if(NOT acetate_dir STREQUAL want_dir)
  message(FATAL_ERROR "sdk_install_test: find_package(Acetate) found \"${acetate_dir}\", "
                      "not the installed package ${want_dir}")
endif()
run_step("build the out-of-tree plugin" "${CMAKE_COMMAND}" --build "${example_build}")
# The installed `acetate check-shaders` compiled every pass of each plugin during that build.
foreach(name tint drop_shadow colour_grade)
  if(NOT step_output MATCHES "acetate check-shaders: com\\.example\\.${name}: [0-9]+ pass sources compiled")
    message(FATAL_ERROR "sdk_install_test: the build did not check ${name}'s shaders:\n${step_output}")
  endif()
endforeach()
message(STATUS "ok: the build checked every plugin's shaders with the installed acetate")

# ---- 3. Check each plugin binary ----
# check_plugin(<name> SOURCES <files>... SHADERS <files>...): <name>.so (not lib<name>.so)
# exports only the entry point, needs no Acetate library, embeds each shader in
# <name>_shaders.hpp and carries the digest of its sources, then its shaders.
function(check_plugin name)
  cmake_parse_arguments(PARSE_ARGV 1 arg "" "" "SOURCES;SHADERS")
  set(plugin "${example_build}/${name}.so")
  require_file("${plugin}")
  if(EXISTS "${example_build}/lib${name}.so")
    message(FATAL_ERROR "sdk_install_test: the plugin was written as lib${name}.so")
  endif()

  run_step("nm -D --defined-only ${name}.so" "${NM}" -D --defined-only "${plugin}")
  string(REPLACE "\n" ";" lines "${step_output}")
  set(exported "")
  set(entry_found FALSE)
  foreach(line IN LISTS lines)
    if(line STREQUAL "")
      continue()
    endif()
    # "<address> <type> <name>[@version]"
    if(NOT line MATCHES "^[0-9a-fA-F]* *([A-Za-z]) ([^ @]+)")
      message(FATAL_ERROR "sdk_install_test: cannot read nm line \"${line}\"")
    endif()
    set(type "${CMAKE_MATCH_1}")
    set(symbol "${CMAKE_MATCH_2}")
    if(symbol STREQUAL "acetate_effect_entry_v1")
      if(NOT type STREQUAL "T")
        message(FATAL_ERROR "sdk_install_test: ${name}.so: acetate_effect_entry_v1 is not a "
                            "global function (nm type ${type})")
      endif()
      set(entry_found TRUE)
    elseif(NOT symbol MATCHES "^(_init|_fini|_edata|_end|__bss_start|__end__)$")
      list(APPEND exported "${type} ${symbol}")
    endif()
  endforeach()
  if(NOT entry_found)
    message(FATAL_ERROR "sdk_install_test: ${name}.so does not export "
                        "acetate_effect_entry_v1:\n${step_output}")
  endif()
  if(exported)
    list(JOIN exported "\n  " exported)
    message(FATAL_ERROR "sdk_install_test: ${name}.so exports more than its entry point:\n"
                        "  ${exported}")
  endif()
  message(STATUS "ok: ${name}.so exports only acetate_effect_entry_v1")

  if(READELF)
    run_step("readelf -d ${name}.so" "${READELF}" -d "${plugin}")
    if(step_output MATCHES "NEEDED[^\n]*acetate")
      message(FATAL_ERROR "sdk_install_test: ${name}.so links an Acetate library; a plugin is "
                          "built against the headers only:\n${step_output}")
    endif()
  endif()

  set(header "${example_build}/${name}_acetate/${name}_shaders.hpp")
  require_file("${header}")
  file(READ "${header}" text)
  set(files "")
  foreach(file IN LISTS arg_SOURCES arg_SHADERS)
    list(APPEND files "${example_src}/${file}")
  endforeach()
  foreach(shader IN LISTS arg_SHADERS)
    string(MAKE_C_IDENTIFIER "${shader}" identifier)
    if(NOT text MATCHES "inline constexpr std::string_view ${identifier} = R\"acetate_glsl\\(")
      message(FATAL_ERROR "sdk_install_test: ${header} does not define ${identifier}:\n${text}")
    endif()
  endforeach()
  expected_digest(digest ${files})
  require_digest("${plugin}" "${digest}")
  message(STATUS "ok: ${name}.so carries the source digest ${digest}")
  set(digest "${digest}" PARENT_SCOPE)
endfunction()

check_plugin(drop_shadow SOURCES drop_shadow.cpp SHADERS drop_shadow_blur.frag drop_shadow.frag)
check_plugin(colour_grade SOURCES colour_grade.cpp SHADERS colour_grade.frag)
# tint last: step 5 edits it and checks the digest it had.
check_plugin(tint SOURCES tint.cpp SHADERS tint.frag)
set(plugin "${example_build}/tint.so")
set(header "${example_build}/tint_acetate/tint_shaders.hpp")

# ---- 4. The installed CLI renders the example scene with the plugins (skip with -DRENDER=OFF) ----
if(NOT DEFINED RENDER OR RENDER)
  set(image "${WORK_DIR}/tint.png")
  file(REMOVE "${image}")
  file(MAKE_DIRECTORY "${WORK_DIR}/cache/mesa" "${WORK_DIR}/cache/xdg")
  # The freshly built plugins are in no registry: --allow-unvalidated loads them with a warning.
  run_step("acetate render scene.json --plugin-path <build> --allow-unvalidated"
    "${CMAKE_COMMAND}" -E env ACETATE_VALIDATION=1 "MESA_SHADER_CACHE_DIR=${WORK_DIR}/cache/mesa"
    "XDG_CACHE_HOME=${WORK_DIR}/cache/xdg"
    "${prefix}/bin/acetate" render "${SOURCE_DIR}/examples/out-of-tree-plugin/scene.json"
    -o "${image}" --plugin-path "${example_build}" --allow-unvalidated)
  require_file("${image}")
  if(NOT step_output MATCHES " 0 violations" OR step_output MATCHES " [1-9][0-9]* violations")
    message(FATAL_ERROR "sdk_install_test: the render reported premultiplied violations:\n${step_output}")
  endif()
  # The scene lists all three; each is loaded from the example's build, with the warning.
  foreach(name tint drop_shadow colour_grade)
    set(loaded "loading unvalidated plugin com\\.example\\.${name} \\([^)\n]*/${name}\\.so\\)")
    if(NOT step_output MATCHES "${loaded}")
      message(FATAL_ERROR "sdk_install_test: the render did not load com.example.${name} from "
                          "${example_build}/${name}.so:\n${step_output}")
    endif()
  endforeach()
  message(STATUS "ok: the render loaded tint, drop_shadow and colour_grade, 0 violations")

  # The plugins must change the render: the same scene with every effect removed (image paths
  # made absolute, since the copy lives elsewhere) gives a different image.
  set(scene_dir "${SOURCE_DIR}/examples/out-of-tree-plugin")
  file(READ "${scene_dir}/scene.json" plain)
  string(JSON floors LENGTH "${plain}" floors)
  math(EXPR last_floor "${floors} - 1")
  foreach(f RANGE ${last_floor})
    string(JSON plain SET "${plain}" floors ${f} effects "[]")
    string(JSON tiles LENGTH "${plain}" floors ${f} tiles)
    math(EXPR last_tile "${tiles} - 1")
    foreach(t RANGE ${last_tile})
      string(JSON image GET "${plain}" floors ${f} tiles ${t} image)
      get_filename_component(image "${scene_dir}/${image}" ABSOLUTE)
      string(JSON plain SET "${plain}" floors ${f} tiles ${t} image "\"${image}\"")
    endforeach()
  endforeach()
  file(WRITE "${WORK_DIR}/plain.json" "${plain}")
  run_step("acetate render (the same scene without the plugins)"
    "${CMAKE_COMMAND}" -E env "MESA_SHADER_CACHE_DIR=${WORK_DIR}/cache/mesa"
    "XDG_CACHE_HOME=${WORK_DIR}/cache/xdg"
    "${prefix}/bin/acetate" render "${WORK_DIR}/plain.json" -o "${WORK_DIR}/plain.png")
  file(SHA256 "${image}" with_plugin)
  file(SHA256 "${WORK_DIR}/plain.png" without_plugin)
  if(with_plugin STREQUAL without_plugin)
    message(FATAL_ERROR "sdk_install_test: the plugins did not change the render")
  endif()
  message(STATUS "ok: the plugins change the render")
endif()

# ---- 5. A changed shader is re-embedded and changes the digest ----
file(APPEND "${example_src}/tint.frag" "// sdk_install_test: edited\n")
run_step("rebuild after editing tint.frag" "${CMAKE_COMMAND}" --build "${example_build}")
file(READ "${header}" text)
if(NOT text MATCHES "// sdk_install_test: edited")
  message(FATAL_ERROR "sdk_install_test: ${header} was not regenerated after tint.frag changed")
endif()
expected_digest(new_digest "${example_src}/tint.cpp" "${example_src}/tint.frag")
if(new_digest STREQUAL digest)
  message(FATAL_ERROR "sdk_install_test: the digest did not change with tint.frag")
endif()
require_digest("${plugin}" "${new_digest}")
message(STATUS "ok: editing tint.frag regenerated tint_shaders.hpp and the digest")

# ---- 6. A GLSL error fails the build, naming the shader file and line, until it is fixed ----
file(APPEND "${example_src}/tint.frag" "float broken() { return undeclared_in_tint; }\n")
file(READ "${example_src}/tint.frag" tint_text)
string(REGEX MATCHALL "\n" newlines "${tint_text}")
list(LENGTH newlines broken_line)  # the appended line is the last; the file ends with \n
foreach(attempt first again)
  execute_process(COMMAND "${CMAKE_COMMAND}" --build "${example_build}"
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(rc EQUAL 0)
    message(FATAL_ERROR "sdk_install_test: the build passed with a GLSL error in tint.frag "
                        "(${attempt} build):\n${out}")
  endif()
  string(REGEX REPLACE "([][+.*()^$?])" "\\\\\\1" quoted "${example_src}/tint.frag")
  if(NOT out MATCHES "${quoted}:${broken_line}: error: 'undeclared_in_tint' : undeclared identifier")
    message(FATAL_ERROR "sdk_install_test: the failed build does not name tint.frag:${broken_line} "
                        "(${attempt} build):\n${out}")
  endif()
endforeach()
message(STATUS "ok: a GLSL error in tint.frag fails the build at tint.frag:${broken_line}, twice")

message(STATUS "sdk_install_test: passed")
