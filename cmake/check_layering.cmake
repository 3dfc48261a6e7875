# Layering check, run by CTest as `cmake -DROOT=<repo> -P check_layering.cmake`.
# Fails when a file includes a header of a module above it (docs/architecture.md §1):
#   topology/  -> Eigen and the standard library only
#   render/    -> render/ only; no planning, topology, app, ImGui
#   planning/  -> planning/, topology/; no render, app, GL, ImGui, ODE (ODE only in planning/physics/)
#   app/       -> everything, but ImGui only inside app/ui/
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
check_dir(topology "[<\"](planning|render|app)/|[<\"](imgui|GLFW|GL|EGL|ode|fcl|urdf|assimp|nlohmann|CLI)")
check_dir(render "[<\"](planning|topology|app)/|[<\"]imgui")
check_dir(planning "[<\"](render|app)/|${GUI}|[<\"]ode/|\"planning/physics/" "^planning/physics/")
check_dir(planning/physics "[<\"](render|app)/|${GUI}")
check_dir(app "[<\"](imgui|backends/)" "^app/ui/")

if(violations)
  list(JOIN violations "\n  " text)
  message(FATAL_ERROR "layering violations (a module includes a module above it):\n  ${text}")
endif()
message(STATUS "layering OK")
