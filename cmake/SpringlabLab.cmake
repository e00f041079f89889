# springlab_add_lab(NAME rope DIR 01_rope)
#
# One lab is two parts: its given code, in framework/labs/<name>/ (the lab's system, scene
# reader, integrators and registration, with the headers that declare the exercises), and
# its exercises, one .cpp file each, in labs/<dir>/ (the student's) and solutions/<dir>/ (the
# reference). The given code calls the exercises through their declarations, so it is
# compiled once and linked with either set:
#   springlab_<name>_given      OBJECT  framework/labs/<name>/src   the given code
#   springlab_<name>_student    STATIC  labs/<dir> + the given objects
#   springlab_<name>_reference  STATIC  solutions/<dir> + the given sources in one unit, so the
#                                       compiler inlines the exercises (a spring's force) into
#                                       the given loops: what `sim --reference` and the
#                                       benchmarks run
#   springlab_<name>_oracle     STATIC  the reference and the given code again, with the lab's
#                                       namespace renamed (springlab::<name>_reference) so
#                                       the grading tests can link it beside the student's code
#                                       and compare the two on random inputs
# Only the framework's headers are on the include path: a student's copy of a header is
# never compiled, so the given code and the exercises always agree on every type.
# The lab is recorded in SPRINGLAB_LABS for the apps and tests.
function(springlab_add_lab)
  cmake_parse_arguments(LAB "" "NAME;DIR" "" ${ARGN})
  set(labs ${SPRINGLAB_LABS})
  list(APPEND labs "${LAB_NAME}:${LAB_DIR}")
  set(SPRINGLAB_LABS ${labs} PARENT_SCOPE)

  set(given_dir ${CMAKE_SOURCE_DIR}/framework/labs/${LAB_NAME})
  file(GLOB given_sources CONFIGURE_DEPENDS ${given_dir}/src/*.cpp)
  set(given springlab_${LAB_NAME}_given)
  add_library(${given} OBJECT ${given_sources})
  target_include_directories(${given} PUBLIC ${given_dir}/include)
  target_link_libraries(${given} PUBLIC springlab_core PRIVATE springlab_internal springlab_warnings)

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
    file(GLOB exercises CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/${folder}/${LAB_DIR}/*.cpp)
    if(tree STREQUAL "student")
      # The exercise objects on their own too: the grader compiles a submission with their
      # flags, and tests/stubs/ swaps one of them into the reference.
      add_library(${target}_objects OBJECT ${exercises})
      target_include_directories(${target}_objects PUBLIC ${given_dir}/include)
      # The student's warnings: never an error for the conversion class (SpringlabWarnings).
      # (springlab_stub_warnings after the warnings: stubs ignore their parameters.)
      target_link_libraries(${target}_objects PUBLIC springlab_core
                            PRIVATE springlab_student_warnings springlab_stub_warnings)
      add_library(${target} STATIC $<TARGET_OBJECTS:${target}_objects> $<TARGET_OBJECTS:${given}>)
    else()
      add_library(${target} STATIC ${exercises} ${given_sources})
    endif()
    target_include_directories(${target} PUBLIC ${given_dir}/include)
    # (springlab_stub_warnings after the warnings: a skeleton's stubs ignore their parameters.)
    target_link_libraries(${target} PUBLIC springlab_core PRIVATE springlab_warnings springlab_stub_warnings)
    if(NOT tree STREQUAL "student")
      # The given sources compile in this target: they see the core's internal headers.
      target_link_libraries(${target} PRIVATE springlab_internal)
    endif()
    if(tree STREQUAL "oracle")
      target_compile_definitions(${target} PRIVATE ${LAB_NAME}=${LAB_NAME}_reference)
    endif()
    if(tree STREQUAL "reference")
      set_target_properties(${target} PROPERTIES UNITY_BUILD ON UNITY_BUILD_BATCH_SIZE 0)
    endif()
  endforeach()

  # The reference's exercises one object per file (not one unit), for tests/stubs/.
  if(SPRINGLAB_BUILD_SOLUTIONS AND SPRINGLAB_BUILD_TESTS)
    file(GLOB exercises CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/solutions/${LAB_DIR}/*.cpp)
    add_library(springlab_${LAB_NAME}_solution_objects OBJECT ${exercises})
    target_link_libraries(springlab_${LAB_NAME}_solution_objects PUBLIC springlab_core PRIVATE springlab_warnings)
    target_include_directories(springlab_${LAB_NAME}_solution_objects PUBLIC ${given_dir}/include)
  endif()

  # What the grader links a submission's exercise objects with: the given objects.
  file(GENERATE OUTPUT ${CMAKE_BINARY_DIR}/grading/${LAB_NAME}_given_objects.txt
       CONTENT "$<JOIN:$<TARGET_OBJECTS:${given}>,\n>\n")
endfunction()
