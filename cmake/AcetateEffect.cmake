# AcetateEffect.cmake -- acetate_add_effect(), the one way to build an Acetate effect plugin.
#
# Used in the Acetate source tree (sdk/CMakeLists.txt includes it, for plugins/) and installed
# with the SDK package (find_package(Acetate) includes it), so in-tree and third-party plugins
# are built the same way.
#
#   acetate_add_effect(<name>
#                      SOURCES <file>...
#                      [SHADERS <glsl file>...]
#                      [OUTPUT_DIRECTORY <dir>]
#                      [INSTALL])
#
# Creates the MODULE library target <name>, written as <name>.so (no "lib" prefix), compiled
# as C++20 without extensions and linked to Acetate::sdk. Symbols are hidden by default, so the
# library exports only acetate_effect_entry_v1 (ACETATE_REGISTER_EFFECT marks it
# ACETATE_EXPORT); static libraries linked into it export nothing either. It is linked with
# --no-undefined, so a missing symbol is a link error rather than a load error.
#
# SOURCES   the plugin's C++ files (headers may be listed too, so they count in the digest).
# SHADERS   GLSL files, each embedded in the generated header <name>_shaders.hpp as
#             inline constexpr std::string_view <identifier> = R"acetate_glsl(...)acetate_glsl";
#           where <identifier> is the file name made a C identifier (tint.frag -> tint_frag).
#           The plugin does #include "<name>_shaders.hpp". The header is regenerated whenever a
#           shader changes.
# OUTPUT_DIRECTORY  where <name>.so is written. Default: ${ACETATE_PLUGIN_OUTPUT_DIR} if that
#           variable is set (the Acetate tree sets it to ${CMAKE_BINARY_DIR}/plugins), else
#           the current binary directory.
# INSTALL   install <name>.so to ${CMAKE_INSTALL_LIBDIR}/acetate/plugins.
#
# The shaders are checked at build time: once <name>.so is linked, `acetate check-shaders` loads
# it, calls its build() with the defaults and with each preset (on a floor with lights, a sun
# and every mask kind it reads, 1 over the middle of the canvas), and compiles every GLSL pass with the preamble the host puts
# before it at load, plain and with the harness's checked built-ins. A GLSL error fails the
# build with the shader file and line (`tint.frag:12: error: ...`). The check uses the
# `acetate` program: in the Acetate tree its target (ACETATE_SHADER_CHECKER), installed the
# package's ACETATE_EXECUTABLE; without either it is skipped with a message. Set
# ACETATE_CHECK_SHADERS to OFF before acetate_add_effect to build without it (plugins broken on
# purpose, sanitizer builds).
#
# ACETATE_SOURCE_DIGEST (the descriptor's source_digest, to which maintainers' sign-offs bind)
# is defined as the lowercase hex SHA-256 of the concatenation of the lowercase hex SHA-256 of
# every file in SOURCES, in the order given, then every file in SHADERS, in the order given
# (no separators, no file names). Editing any of those files re-runs CMake's configure step so
# the digest is never stale.

if(CMAKE_VERSION VERSION_LESS 3.20)
  message(FATAL_ERROR "acetate_add_effect needs CMake 3.20 or newer (this is ${CMAKE_VERSION})")
endif()

include_guard(GLOBAL)
include(GNUInstallDirs)

# Computes the source digest of FILES (absolute paths, in order) into OUT_VAR.
function(acetate_source_digest out_var)
  set(hashes "")
  foreach(file IN LISTS ARGN)
    file(SHA256 "${file}" hash)
    string(APPEND hashes "${hash}")
  endforeach()
  string(SHA256 digest "${hashes}")
  set(${out_var} "${digest}" PARENT_SCOPE)
endfunction()

function(acetate_add_effect name)
  cmake_parse_arguments(PARSE_ARGV 1 arg "INSTALL" "OUTPUT_DIRECTORY" "SOURCES;SHADERS")
  if(arg_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "acetate_add_effect(${name}): unexpected arguments: ${arg_UNPARSED_ARGUMENTS}")
  endif()
  if(NOT name MATCHES "^[A-Za-z0-9_.-]+$")
    message(FATAL_ERROR "acetate_add_effect(${name}): the name may use only letters, digits, _ . -")
  endif()
  if(NOT arg_SOURCES)
    message(FATAL_ERROR "acetate_add_effect(${name}): SOURCES is required")
  endif()
  if(NOT TARGET Acetate::sdk)
    message(FATAL_ERROR "acetate_add_effect(${name}): the target Acetate::sdk does not exist; "
                        "call find_package(Acetate REQUIRED) first")
  endif()

  # Absolute paths, in the order given.
  set(sources "")
  foreach(src IN LISTS arg_SOURCES)
    cmake_path(ABSOLUTE_PATH src BASE_DIRECTORY "${CMAKE_CURRENT_SOURCE_DIR}" NORMALIZE
               OUTPUT_VARIABLE abs)
    if(NOT EXISTS "${abs}" OR IS_DIRECTORY "${abs}")
      message(FATAL_ERROR "acetate_add_effect(${name}): source file not found: ${abs}")
    endif()
    list(APPEND sources "${abs}")
  endforeach()
  set(shaders "")
  set(identifiers "")
  foreach(src IN LISTS arg_SHADERS)
    cmake_path(ABSOLUTE_PATH src BASE_DIRECTORY "${CMAKE_CURRENT_SOURCE_DIR}" NORMALIZE
               OUTPUT_VARIABLE abs)
    if(NOT EXISTS "${abs}" OR IS_DIRECTORY "${abs}")
      message(FATAL_ERROR "acetate_add_effect(${name}): shader file not found: ${abs}")
    endif()
    if(abs MATCHES "[|]")
      message(FATAL_ERROR "acetate_add_effect(${name}): a shader path may not contain '|': ${abs}")
    endif()
    cmake_path(GET abs FILENAME file_name)
    string(MAKE_C_IDENTIFIER "${file_name}" identifier)
    if(identifier IN_LIST identifiers)
      message(FATAL_ERROR "acetate_add_effect(${name}): two shaders map to the same identifier "
                          "\"${identifier}\"; rename one (${abs})")
    endif()
    list(APPEND identifiers "${identifier}")
    list(APPEND shaders "${abs}")
  endforeach()

  add_library(${name} MODULE ${sources})
  target_link_libraries(${name} PRIVATE Acetate::sdk)
  target_compile_features(${name} PRIVATE cxx_std_20)
  set_target_properties(${name} PROPERTIES
    PREFIX ""
    SUFFIX ".so"
    OUTPUT_NAME "${name}"
    CXX_EXTENSIONS OFF
    CXX_VISIBILITY_PRESET hidden
    VISIBILITY_INLINES_HIDDEN ON
    POSITION_INDEPENDENT_CODE ON)
  # A sanitizer build leaves the sanitizer's symbols to the host executable that loads the
  # plugin, so it cannot insist on --no-undefined.
  if(ACETATE_SANITIZE)
    target_link_options(${name} PRIVATE "LINKER:--exclude-libs,ALL")
  else()
    target_link_options(${name} PRIVATE "LINKER:--no-undefined" "LINKER:--exclude-libs,ALL")
    # Hidden visibility cannot hide what libstdc++'s headers mark default (std::to_string
    # instantiates __to_chars_10_impl, and a GNU-unique table that also keeps the library from
    # unloading): a version script makes the entry point the only exported symbol.
    set(exports "${CMAKE_CURRENT_BINARY_DIR}/${name}_acetate/exports.map")
    file(WRITE "${exports}" "{ global: acetate_effect_entry_v1; local: *; };\n")
    target_link_options(${name} PRIVATE "LINKER:--version-script=${exports}")
  endif()

  # Output directory: argument, then ACETATE_PLUGIN_OUTPUT_DIR, then CMake's default.
  set(out_dir "")
  if(arg_OUTPUT_DIRECTORY)
    set(out_dir "${arg_OUTPUT_DIRECTORY}")
  elseif(DEFINED ACETATE_PLUGIN_OUTPUT_DIR AND NOT ACETATE_PLUGIN_OUTPUT_DIR STREQUAL "")
    set(out_dir "${ACETATE_PLUGIN_OUTPUT_DIR}")
  endif()
  if(out_dir)
    cmake_path(ABSOLUTE_PATH out_dir BASE_DIRECTORY "${CMAKE_CURRENT_BINARY_DIR}" NORMALIZE)
    set_target_properties(${name} PROPERTIES LIBRARY_OUTPUT_DIRECTORY "${out_dir}")
  endif()

  # The source digest, recomputed whenever one of its files changes.
  acetate_source_digest(digest ${sources} ${shaders})
  target_compile_definitions(${name} PRIVATE "ACETATE_SOURCE_DIGEST=\"${digest}\"")
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${sources} ${shaders})
  set_target_properties(${name} PROPERTIES ACETATE_SOURCE_DIGEST "${digest}")

  # Embedded shaders: <binary dir>/<name>_acetate/<name>_shaders.hpp.
  if(shaders)
    set(gen_dir "${CMAKE_CURRENT_BINARY_DIR}/${name}_acetate")
    set(header "${gen_dir}/${name}_shaders.hpp")
    set(script "${CMAKE_CURRENT_FUNCTION_LIST_DIR}/AcetateEmbedGlsl.cmake")
    string(REPLACE ";" "|" shader_arg "${shaders}")
    add_custom_command(
      OUTPUT "${header}"
      COMMAND "${CMAKE_COMMAND}" "-DACETATE_OUT=${header}" "-DACETATE_SHADERS=${shader_arg}"
              -P "${script}"
      DEPENDS ${shaders} "${script}"
      COMMENT "Embedding the shaders of ${name}"
      VERBATIM)
    target_sources(${name} PRIVATE "${header}")
    target_include_directories(${name} PRIVATE "${gen_dir}")
  endif()

  # The shaders checked at build time, into a stamp file: a failed check leaves none, so the
  # next build checks again.
  if(NOT DEFINED ACETATE_CHECK_SHADERS OR ACETATE_CHECK_SHADERS)
    set(checker "")
    if(DEFINED ACETATE_SHADER_CHECKER)
      set(checker "${ACETATE_SHADER_CHECKER}")
    elseif(DEFINED ACETATE_EXECUTABLE)
      set(checker "${ACETATE_EXECUTABLE}")
    endif()
    if(checker)
      set(stamp "${CMAKE_CURRENT_BINARY_DIR}/${name}_acetate/shaders.checked")
      set(shader_flags "")
      foreach(shader IN LISTS shaders)
        list(APPEND shader_flags --shader "${shader}")
      endforeach()
      add_custom_command(
        OUTPUT "${stamp}"
        COMMAND "${checker}" check-shaders "$<TARGET_FILE:${name}>" ${shader_flags}
        COMMAND "${CMAKE_COMMAND}" -E touch "${stamp}"
        DEPENDS ${name} ${shaders}
        COMMENT "Checking the shaders of ${name}"
        VERBATIM)
      add_custom_target(${name}_shaders_checked ALL DEPENDS "${stamp}")
    else()
      message(STATUS "acetate_add_effect(${name}): shaders not checked at build time: no "
                     "installed `acetate` (ACETATE_EXECUTABLE)")
    endif()
  endif()

  if(arg_INSTALL)
    install(TARGETS ${name}
      LIBRARY DESTINATION "${CMAKE_INSTALL_LIBDIR}/acetate/plugins"
      RUNTIME DESTINATION "${CMAKE_INSTALL_LIBDIR}/acetate/plugins")
  endif()
endfunction()
