# Installation (`cmake --install build --prefix P`):
#   P/lib/libtopology.a, librender.a, libplanning.a, libplanning_physics.a
#   P/include/{topology,render,planning,planning/physics}/*.h   (internal/ headers are not public)
#   P/lib/cmake/topoplan/topoplan{Config,ConfigVersion,Targets}.cmake
#       -> find_package(topoplan) gives topoplan::topology, topoplan::render, topoplan::planning
#          and topoplan::physics (the ODE grasp simulation, target planning_physics here)
#   P/bin/topoplan and its assets in P/share/topoplan (found relative to the binary, see
#   base/assets.cc AssetRoot()).
#
# The libraries are static, so the consumer links their private dependencies too. The package
# config finds each of them again: the list is derived below from the libraries' link interfaces,
# so a new dependency either maps to a known package or stops the configure step with a message.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(TOPOPLAN_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/topoplan)
set(TOPOPLAN_INSTALL_ASSETDIR ${CMAKE_INSTALL_DATADIR}/topoplan)

set(_topoplan_exported)
foreach(t base topology render planning planning_physics)
  if(TARGET ${t})
    list(APPEND _topoplan_exported ${t})
  endif()
endforeach()
if(TARGET planning_physics)
  set_target_properties(planning_physics PROPERTIES EXPORT_NAME physics)
  add_library(topoplan::physics ALIAS planning_physics)
endif()

# How the package config finds what an exported library links (first matching regex wins).
set(_topoplan_dependency_rules
  "^PkgConfig::"                    "pkg"
  "^Eigen3::"                       "find_dependency(Eigen3 3.4 NO_MODULE)"
  "^assimp::"                       "find_dependency(assimp)"
  "^fcl$"                           "find_dependency(fcl)"
  "^nlohmann_json::"                "find_dependency(nlohmann_json 3.10)"
  "^(urdfdom|urdfdom_headers|console_bridge)::" "find_dependency(urdfdom)"
  "^mujoco::"                       "find_dependency(mujoco)"
  "^topoplan::ompl$"                "_topoplan_find_ompl()")

# Plain library paths (urdfdom's and OMPL's CMake variables) would freeze this machine's files
# into the exported targets; the installed interface names imported targets instead.
function(_topoplan_install_name lib out)
  if(lib MATCHES "^/.*/lib(urdfdom_[a-z_]+)\\.so$")
    set(${out} "urdfdom::${CMAKE_MATCH_1}" PARENT_SCOPE)
  elseif(lib MATCHES "^/.*/libompl\\.so")
    set(${out} "topoplan::ompl" PARENT_SCOPE)
  else()
    set(${out} "${lib}" PARENT_SCOPE)
  endif()
endfunction()

set(_topoplan_dependency_lines)
foreach(t IN LISTS _topoplan_exported)
  get_target_property(libs ${t} INTERFACE_LINK_LIBRARIES)
  if(NOT libs)
    continue()
  endif()
  set(relinked)
  foreach(item IN LISTS libs)
    set(lib "${item}")
    if(lib MATCHES "^\\$<LINK_ONLY:(.*)>$")
      set(lib "${CMAKE_MATCH_1}")
    endif()
    _topoplan_install_name("${lib}" installed)
    if(installed STREQUAL lib)
      list(APPEND relinked "${item}")
    else()
      # A file carries no usage requirements: link-only keeps the target's the same.
      list(APPEND relinked "$<BUILD_INTERFACE:${item}>"
                           "$<INSTALL_INTERFACE:$<LINK_ONLY:${installed}>>")
    endif()
    if(installed IN_LIST _topoplan_exported OR NOT installed MATCHES "::|^[A-Za-z0-9_]+$")
      continue()  # one of ours, a file path, a flag or a generator expression
    endif()
    set(line "")
    list(LENGTH _topoplan_dependency_rules n)
    math(EXPR last "${n} - 1")
    foreach(k RANGE 0 ${last} 2)
      math(EXPR k1 "${k} + 1")
      list(GET _topoplan_dependency_rules ${k} regex)
      if(installed MATCHES "${regex}")
        list(GET _topoplan_dependency_rules ${k1} line)
        break()
      endif()
    endforeach()
    if(line STREQUAL "pkg")
      string(REPLACE "PkgConfig::" "" prefix "${installed}")
      set(line "_topoplan_find_pkg(${prefix} ${${prefix}_MODULE_NAME})")
    elseif(line STREQUAL "" AND TARGET ${installed})
      message(FATAL_ERROR "${t} links ${installed}: add how topoplanConfig.cmake finds it to "
                          "_topoplan_dependency_rules in cmake/TopoplanInstall.cmake")
    endif()
    if(NOT line STREQUAL "")
      list(APPEND _topoplan_dependency_lines "${line}")
    endif()
  endforeach()
  set_target_properties(${t} PROPERTIES INTERFACE_LINK_LIBRARIES "${relinked}")
endforeach()
list(REMOVE_DUPLICATES _topoplan_dependency_lines)
list(JOIN _topoplan_dependency_lines "\n" TOPOPLAN_CONFIG_DEPENDENCIES)

# Libraries, headers and the package files.
install(TARGETS ${_topoplan_exported} EXPORT topoplanTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
foreach(module base topology render planning)
  if(TARGET ${module})
    install(DIRECTORY ${PROJECT_SOURCE_DIR}/${module}/
      DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/${module}
      FILES_MATCHING PATTERN "*.h" PATTERN "internal" EXCLUDE PATTERN "physics" EXCLUDE)
  endif()
endforeach()
if(TARGET planning_physics)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/planning/physics/
    DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/planning/physics
    FILES_MATCHING PATTERN "*.h" PATTERN "internal" EXCLUDE)
endif()
install(EXPORT topoplanTargets NAMESPACE topoplan:: DESTINATION ${TOPOPLAN_INSTALL_CMAKEDIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/topoplanConfig.cmake.in
  ${PROJECT_BINARY_DIR}/topoplanConfig.cmake INSTALL_DESTINATION ${TOPOPLAN_INSTALL_CMAKEDIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/topoplanConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/topoplanConfig.cmake
              ${PROJECT_BINARY_DIR}/topoplanConfigVersion.cmake
  DESTINATION ${TOPOPLAN_INSTALL_CMAKEDIR})

# The command-line tool and its data. AssetRoot() looks for <exe dir>/<this relative path> before
# falling back to the source tree's assets/ (so a build-tree binary still runs in place).
install(TARGETS topoplan topoplan-full RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/assets/ DESTINATION ${TOPOPLAN_INSTALL_ASSETDIR})
file(RELATIVE_PATH _topoplan_asset_rel ${CMAKE_INSTALL_FULL_BINDIR}
     ${CMAKE_INSTALL_FULL_DATADIR}/topoplan)
target_compile_definitions(base PRIVATE
  TOPOPLAN_INSTALLED_ASSET_DIR="${_topoplan_asset_rel}")
