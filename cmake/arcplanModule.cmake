# arcplan_add_module(NAME SOURCES ... DEPENDS ...)
# One library per module folder: public headers in <module>/include/arcplan/<module>/,
# exported as arcplan::<module>.
function(arcplan_add_module name)
  cmake_parse_arguments(ARG "" "" "SOURCES;PUBLIC_DEPS;PRIVATE_DEPS" ${ARGN})
  add_library(arcplan_${name} ${ARG_SOURCES})
  add_library(arcplan::${name} ALIAS arcplan_${name})
  set_target_properties(arcplan_${name} PROPERTIES EXPORT_NAME ${name} OUTPUT_NAME arcplan_${name}
                        POSITION_INDEPENDENT_CODE ON)
  target_include_directories(arcplan_${name} PUBLIC
    $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_compile_features(arcplan_${name} PUBLIC cxx_std_17)
  target_compile_options(arcplan_${name} PRIVATE ${ARCPLAN_WARNINGS})
  target_link_libraries(arcplan_${name} PUBLIC ${ARG_PUBLIC_DEPS} PRIVATE ${ARG_PRIVATE_DEPS})
  install(TARGETS arcplan_${name} EXPORT arcplanTargets
          ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
          LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
  install(DIRECTORY include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
endfunction()
