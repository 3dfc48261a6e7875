# topoplan_add_test(NAME name SOURCES a.cc [b.cc] LIBS lib... LABEL unit|property|snapshot [ENV K=V]
#                   [FIXTURES fixture] [TIMEOUT seconds])
# Builds one GoogleTest executable and registers its cases with CTest under the given labels.
function(topoplan_add_test)
  cmake_parse_arguments(T "" "NAME;FIXTURES;TIMEOUT" "SOURCES;LIBS;LABELS;ENV" ${ARGN})
  add_executable(${T_NAME} ${T_SOURCES})
  target_link_libraries(${T_NAME} PRIVATE ${T_LIBS} GTest::gtest GTest::gtest_main)
  target_include_directories(${T_NAME} PRIVATE ${PROJECT_SOURCE_DIR})
  target_compile_definitions(${T_NAME} PRIVATE
    TOPOPLAN_SOURCE_DIR="${PROJECT_SOURCE_DIR}" TOPOPLAN_BINARY_DIR="${PROJECT_BINARY_DIR}")
  # Test drivers compile at -O1 in Release (the libraries they test keep -O3): their time is in
  # the front end and in the libraries, and -O1 compiles them about 20 % faster.
  target_compile_options(${T_NAME} PRIVATE $<$<CONFIG:Release>:-O1>)
  # One label per executable (gtest_discover_tests cannot carry a list of labels); ENV entries
  # are joined the same way, so pass at most one.
  set(fixtures)
  if(T_FIXTURES)
    set(fixtures FIXTURES_REQUIRED ${T_FIXTURES})
  endif()
  if(T_TIMEOUT)
    list(APPEND fixtures TIMEOUT ${T_TIMEOUT})
  endif()
  if(T_ENV)
    list(APPEND fixtures ENVIRONMENT "${T_ENV}")
  endif()
  gtest_discover_tests(${T_NAME}
    PROPERTIES LABELS "${T_LABELS}" ${fixtures}
    DISCOVERY_TIMEOUT 60)
endfunction()

# topoplan_add_library(name SOURCES ... PUBLIC_LIBS ... PRIVATE_LIBS ...)
# One static library per module, include paths rooted at the repository (at <prefix>/include once
# installed, see TopoplanInstall.cmake), alias topoplan::name.
function(topoplan_add_library name)
  cmake_parse_arguments(L "" "" "SOURCES;PUBLIC_LIBS;PRIVATE_LIBS" ${ARGN})
  add_library(${name} STATIC ${L_SOURCES})
  add_library(topoplan::${name} ALIAS ${name})
  target_include_directories(${name} PUBLIC $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}>)
  target_link_libraries(${name} PUBLIC ${L_PUBLIC_LIBS} PRIVATE ${L_PRIVATE_LIBS})
endfunction()
