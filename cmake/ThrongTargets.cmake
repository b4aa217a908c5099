# throng_add_library(<layer> SOURCES ... [PUBLIC_DEPS ...] [PRIVATE_DEPS ...])
#
# One static library per layer, target throng_<layer> with alias throng::<layer>. Public headers live in
# <layer>/include/throng/<layer>/ and are included as <throng/<layer>/name.h>; everything under src/ is
# private to the layer.
function(throng_add_library layer)
  cmake_parse_arguments(ARG "" "" "SOURCES;PUBLIC_DEPS;PRIVATE_DEPS" ${ARGN})
  add_library(throng_${layer} STATIC ${ARG_SOURCES})
  add_library(throng::${layer} ALIAS throng_${layer})
  target_include_directories(throng_${layer}
    PUBLIC ${CMAKE_CURRENT_SOURCE_DIR}/include
    PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/src)
  target_link_libraries(throng_${layer} PUBLIC ${ARG_PUBLIC_DEPS} PRIVATE ${ARG_PRIVATE_DEPS} throng_warnings)
  set_target_properties(throng_${layer} PROPERTIES POSITION_INDEPENDENT_CODE ON
    CXX_VISIBILITY_PRESET hidden VISIBILITY_INLINES_HIDDEN ON)
endfunction()
