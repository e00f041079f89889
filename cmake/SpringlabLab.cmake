# springlab_add_lab(NAME rope DIR 01_rope)
#
# Builds one lab from each tree that is present:
#   springlab_<name>_student    labs/<dir>       the student's code
#   springlab_<name>_reference  solutions/<dir>  the reference, for the reference app
#   springlab_<name>_oracle     solutions/<dir>  the reference again, with its namespace
#                                                renamed (springlab::<name>_reference) so the
#                                                grading tests can link it beside the student's
#                                                code and compare the two on random inputs.
# and records the lab in SPRINGLAB_LABS for the apps and tests.
function(springlab_add_lab)
  cmake_parse_arguments(LAB "" "NAME;DIR" "" ${ARGN})
  set(labs ${SPRINGLAB_LABS})
  list(APPEND labs "${LAB_NAME}:${LAB_DIR}")
  set(SPRINGLAB_LABS ${labs} PARENT_SCOPE)

  set(trees)
  if(SPRINGLAB_BUILD_LABS AND EXISTS ${CMAKE_SOURCE_DIR}/labs/${LAB_DIR})
    list(APPEND trees "student:labs")
  endif()
  if(SPRINGLAB_BUILD_SOLUTIONS)
    list(APPEND trees "reference:solutions" "oracle:solutions")
  endif()

  foreach(entry IN LISTS trees)
    string(REPLACE ":" ";" parts ${entry})
    list(GET parts 0 tree)
    list(GET parts 1 folder)
    set(target springlab_${LAB_NAME}_${tree})
    file(GLOB sources CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/${folder}/${LAB_DIR}/*.cpp)
    add_library(${target} STATIC ${sources})
    # The oracle keeps its headers to itself, so tests always see the graded tree's headers.
    if(tree STREQUAL "oracle")
      target_include_directories(${target} PRIVATE ${CMAKE_SOURCE_DIR}/${folder}/${LAB_DIR})
    else()
      target_include_directories(${target} PUBLIC ${CMAKE_SOURCE_DIR}/${folder}/${LAB_DIR})
    endif()
    target_link_libraries(${target} PUBLIC springlab_core PRIVATE springlab_warnings)
    # A skeleton's stubs do not use their parameters yet.
    target_compile_options(${target} PRIVATE -Wno-unused-parameter)
    if(tree STREQUAL "oracle")
      target_compile_definitions(${target} PRIVATE ${LAB_NAME}=${LAB_NAME}_reference)
    endif()
    # The reference is what the benchmarks and `sim --reference` time: one translation unit
    # lets the compiler inline the exercises (a spring's force) into the given loops.
    # Students' trees stay one file per unit, as the grader compiles them.
    if(tree STREQUAL "reference")
      set_target_properties(${target} PROPERTIES UNITY_BUILD ON UNITY_BUILD_BATCH_SIZE 0)
    endif()
  endforeach()
endfunction()
