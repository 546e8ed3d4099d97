# Checks that every file of src/obscura/<layer>/ includes only headers of its
# own layer and of the layers below it (the transitive closure of the DEPENDS
# declared in src/obscura/CMakeLists.txt), and that every folder is a
# declared layer. Run as
#   cmake -DLAYERS_FILE=<build>/obscura_layers.cmake -DSOURCE_ROOT=<dir holding obscura/> -P check_layers.cmake
# Exits non-zero, listing each offending include with its file and line.
cmake_minimum_required(VERSION 3.25)
if(NOT LAYERS_FILE OR NOT SOURCE_ROOT)
  message(FATAL_ERROR "check_layers: set LAYERS_FILE and SOURCE_ROOT")
endif()
include(${LAYERS_FILE})
get_filename_component(SOURCE_ROOT "${SOURCE_ROOT}" ABSOLUTE)

# Transitive closure of a layer's declared dependencies.
function(layer_closure layer out)
  set(seen)
  set(queue ${OBSCURA_LAYER_${layer}_DEPENDS})
  while(queue)
    list(POP_FRONT queue next)
    if(NOT next IN_LIST seen)
      list(APPEND seen ${next})
      list(APPEND queue ${OBSCURA_LAYER_${next}_DEPENDS})
    endif()
  endwhile()
  set(${out} ${seen} PARENT_SCOPE)
endfunction()

set(problems "")
file(GLOB folders LIST_DIRECTORIES true RELATIVE ${SOURCE_ROOT}/obscura ${SOURCE_ROOT}/obscura/*)
foreach(folder IN LISTS folders)
  if(IS_DIRECTORY ${SOURCE_ROOT}/obscura/${folder} AND NOT folder IN_LIST OBSCURA_LAYERS)
    string(APPEND problems "  src/obscura/${folder}/ is not a declared layer (src/obscura/CMakeLists.txt)\n")
  endif()
endforeach()

set(checked 0)
foreach(layer IN LISTS OBSCURA_LAYERS)
  layer_closure(${layer} allowed)
  list(APPEND allowed ${layer})
  file(GLOB_RECURSE files RELATIVE ${SOURCE_ROOT} ${SOURCE_ROOT}/obscura/${layer}/*.h
       ${SOURCE_ROOT}/obscura/${layer}/*.cpp ${SOURCE_ROOT}/obscura/${layer}/*.cu
       ${SOURCE_ROOT}/obscura/${layer}/*.cuh)
  foreach(file IN LISTS files)
    math(EXPR checked "${checked} + 1")
    file(STRINGS ${SOURCE_ROOT}/${file} lines REGEX "^[ \t]*#[ \t]*include[ \t]*[\"<]obscura/")
    foreach(line IN LISTS lines)
      string(REGEX MATCH "obscura/([A-Za-z0-9_]+)/" _ "${line}")
      set(target_layer "${CMAKE_MATCH_1}")
      if(target_layer STREQUAL "")
        string(APPEND problems "  ${file}: ${line}: includes a header outside every layer\n")
      elseif(NOT target_layer IN_LIST allowed)
        string(APPEND problems "  ${file}: ${line}: layer '${layer}' may not include '${target_layer}' (it may include: ${allowed})\n")
      endif()
    endforeach()
  endforeach()
endforeach()

if(problems)
  message(FATAL_ERROR "check_layers: includes that run up the layers:\n${problems}")
endif()
message(STATUS "check_layers: ${checked} files, every include within its layer or below")
