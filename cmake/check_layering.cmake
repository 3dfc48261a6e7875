# Layering check, run by CTest as `cmake -DROOT=<repo> -P check_layering.cmake`.
# Fails when a file includes a header of a module above it (docs/architecture.md §1):
#   base/      -> the standard library, Eigen, nlohmann-json only (the lowest layer)
#   topology/  -> base/, Eigen and the standard library only
#   render/    -> render/ only; no planning, topology, app, ImGui
#   planning/  -> planning/, topology/; no render, app, GL, ImGui, ODE, MuJoCo (only in planning/physics/)
#   visualize/ -> planning/, render/, topology/, base/; no app, GL windows or CLI
#   app/       -> everything, but ImGui only inside app/viewer/
#   python/    -> the libraries, never app/
#   planning/<sub>/ -> only the planning sub-layers before it: robot, collision, features, motion,
#                      grasp, physics
if(NOT ROOT)
  message(FATAL_ERROR "usage: cmake -DROOT=<repo> -P check_layering.cmake")
endif()

set(violations "")
function(check_dir dir forbidden_regex)
  file(GLOB_RECURSE files "${ROOT}/${dir}/*.h" "${ROOT}/${dir}/*.cc" "${ROOT}/${dir}/*.cpp")
  foreach(f IN LISTS files)
    file(RELATIVE_PATH rel "${ROOT}" "${f}")
    if(ARGV2 AND rel MATCHES "${ARGV2}")
      continue()
    endif()
    file(STRINGS "${f}" lines REGEX "^[ \t]*#[ \t]*include")
    foreach(line IN LISTS lines)
      if(line MATCHES "${forbidden_regex}")
        string(STRIP "${line}" line)
        list(APPEND violations "${rel}: ${line}")
      endif()
    endforeach()
  endforeach()
  set(violations "${violations}" PARENT_SCOPE)
endfunction()

set(GUI "[<\"](imgui|GLFW/|GL/|EGL/|backends/)")
check_dir(base "[<\"](topology|render|planning|visualize|app)/|[<\"](imgui|GLFW|GL|EGL|ode|fcl|urdf|assimp|CLI)")
check_dir(topology "[<\"](planning|render|visualize|app)/|[<\"](imgui|GLFW|GL|EGL|ode|fcl|urdf|assimp|nlohmann|CLI)")
check_dir(render "[<\"](planning|topology|visualize|app)/|[<\"]imgui")
check_dir(planning "[<\"](render|visualize|app)/|${GUI}|[<\"](ode|mujoco)/|\"planning/physics/" "^planning/physics/")
check_dir(planning/physics "[<\"](render|visualize|app)/|${GUI}")
check_dir(visualize "[<\"]app/|${GUI}|[<\"](CLI)/")
check_dir(python "\"app/")
# Inside planning/, sub-layers in order: each folder uses only the folders before it.
set(planning_order robot collision features motion grasp physics)
list(LENGTH planning_order n)
math(EXPR last "${n} - 1")
foreach(i RANGE 0 ${last})
  list(GET planning_order ${i} here)
  math(EXPR next "${i} + 1")
  set(above "")
  if(next LESS n)
    list(SUBLIST planning_order ${next} -1 above)
  endif()
  if(above)
    list(JOIN above "|" above_regex)
    check_dir(planning/${here} "\"planning/(${above_regex})/")
  endif()
endforeach()
# Every planning header lives in one of the sub-layer folders (or is shared by all of them).
file(GLOB loose "${ROOT}/planning/*.h" "${ROOT}/planning/*.cc")
foreach(f IN LISTS loose)
  file(RELATIVE_PATH rel "${ROOT}" "${f}")
  if(NOT rel MATCHES "^planning/(json_reader|enum_names|random)\\.")
    list(APPEND violations "${rel}: planning sources belong in ${planning_order}")
  endif()
endforeach()
check_dir(app "[<\"](imgui|backends/)" "^app/viewer/")

if(violations)
  list(JOIN violations "\n  " text)
  message(FATAL_ERROR "layering violations (a module includes a module above it):\n  ${text}")
endif()
message(STATUS "layering OK")
