# Third-party dependencies of arcplan, shared by the build tree and by the installed
# arcplanConfig.cmake so that a consumer gets exactly the same imported targets.
# Every package comes from Debian 12 (see scripts/setup).
include(CMakeFindDependencyMacro)

find_dependency(Eigen3 3.3 NO_MODULE)
find_dependency(fcl 0.7)
find_dependency(assimp)
find_dependency(urdfdom)
find_dependency(yaml-cpp)
find_dependency(nlohmann_json 3)
find_dependency(muparser)
find_dependency(ompl 1.5)

# OMPL 1.5 exports variables only; wrap them in an imported target so every module links
# the same way (target_link_libraries(... ompl::ompl)).
if(NOT TARGET ompl::ompl)
  add_library(ompl::ompl INTERFACE IMPORTED)
  set_target_properties(ompl::ompl PROPERTIES
    INTERFACE_INCLUDE_DIRECTORIES "${OMPL_INCLUDE_DIRS}"
    INTERFACE_LINK_LIBRARIES "${OMPL_LIBRARIES}")
endif()

# urdfdom's config exports per-library targets plus a variable; bundle them.
if(NOT TARGET arcplan_deps::urdfdom)
  add_library(arcplan_deps::urdfdom INTERFACE IMPORTED)
  set_target_properties(arcplan_deps::urdfdom PROPERTIES
    INTERFACE_INCLUDE_DIRECTORIES "${urdfdom_INCLUDE_DIRS}"
    INTERFACE_LINK_LIBRARIES "${urdfdom_LIBRARIES}")
endif()
