# springlab_read_manifests([ROOT dir]): the labs of the tree at ROOT (default: the source
# folder), one per manifest tests/NN_<id>/exercises.json (the one list of labs, exercises,
# files, functions and points; tools/springlab_grader/labs.py reads the same files for the
# grader and the `springlab` script). Sets, in the caller's scope:
#   SPRINGLAB_LAB_IDS            the labs' ids in the order of their folders (rope;net;softbody)
#   SPRINGLAB_LAB_<id>_DIR       the lab's folder in labs/, solutions/, tests/ (01_rope)
#   SPRINGLAB_LAB_<id>_FILES     its exercise files, one per exercise (spring_force.cpp;...)
#   SPRINGLAB_LAB_<id>_BUILDS_ON the labs whose exercises its scenes run too (the manifest's
#                                "builds_on": the net's and the soft body's scenes offer the
#                                rope's integrators), before the lab itself in a program
# Editing a manifest re-runs CMake. A malformed one stops the configure naming file and field.
function(springlab_read_manifests)
  cmake_parse_arguments(READ "" "ROOT" "" ${ARGN})
  if(NOT READ_ROOT)
    set(READ_ROOT ${CMAKE_SOURCE_DIR})
  endif()
  file(GLOB manifests CONFIGURE_DEPENDS ${READ_ROOT}/tests/*/exercises.json)
  list(SORT manifests)
  set(ids "")
  foreach(manifest IN LISTS manifests)
    get_filename_component(folder_path ${manifest} DIRECTORY)
    get_filename_component(folder ${folder_path} NAME)
    if(NOT folder MATCHES "^[0-9][0-9]_([a-z][a-z0-9_]*)$")
      continue()
    endif()
    set(folder_id ${CMAKE_MATCH_1})
    set_property(DIRECTORY ${CMAKE_SOURCE_DIR} APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${manifest})
    file(READ ${manifest} text)
    string(JSON id ERROR_VARIABLE error GET "${text}" lab)
    if(error OR NOT id STREQUAL folder_id)
      message(FATAL_ERROR "${manifest}: lab: must be the lab's id '${folder_id}' (the folder is NN_<id>) ${error}")
    endif()
    string(JSON count ERROR_VARIABLE error LENGTH "${text}" exercises)
    if(error)
      message(FATAL_ERROR "${manifest}: exercises: ${error}")
    endif()
    set(files "")
    if(count GREATER 0)
      math(EXPR last "${count} - 1")
      foreach(i RANGE ${last})
        string(JSON file ERROR_VARIABLE error GET "${text}" exercises ${i} file)
        if(error OR NOT file MATCHES "^[A-Za-z0-9_]+[.]cpp$")
          message(FATAL_ERROR "${manifest}: exercises[${i}].file: must be the exercise's file name (name.cpp) ${error}")
        endif()
        list(APPEND files ${file})
      endforeach()
    endif()
    # "builds_on": optional, a list of lab ids; checked against the labs below, once all are read.
    set(builds_on "")
    string(JSON kind ERROR_VARIABLE error TYPE "${text}" builds_on)
    if(NOT error)
      string(JSON count ERROR_VARIABLE error LENGTH "${text}" builds_on)
      if(NOT kind STREQUAL "ARRAY" OR error)
        message(FATAL_ERROR "${manifest}: builds_on: must be a list of lab ids ([\"rope\"])")
      endif()
      if(count GREATER 0)
        math(EXPR last "${count} - 1")
        foreach(i RANGE ${last})
          string(JSON base GET "${text}" builds_on ${i})
          list(APPEND builds_on ${base})
        endforeach()
      endif()
    endif()
    set(builds_on_${id} ${builds_on})
    set(manifest_of_${id} ${manifest})
    list(APPEND ids ${id})
    set(SPRINGLAB_LAB_${id}_DIR ${folder} PARENT_SCOPE)
    set(SPRINGLAB_LAB_${id}_FILES ${files} PARENT_SCOPE)
    set(SPRINGLAB_LAB_${id}_BUILDS_ON ${builds_on} PARENT_SCOPE)
  endforeach()
  if(NOT ids)
    message(FATAL_ERROR "${READ_ROOT}/tests: no NN_<lab>/exercises.json manifests: no labs to build")
  endif()
  foreach(id IN LISTS ids)
    foreach(base IN LISTS builds_on_${id})
      if(NOT base IN_LIST ids OR base STREQUAL id)
        message(FATAL_ERROR "${manifest_of_${id}}: builds_on: '${base}' is not another lab's id (${ids})")
      endif()
    endforeach()
  endforeach()
  set(SPRINGLAB_LAB_IDS ${ids} PARENT_SCOPE)
endfunction()

# springlab_write_register(FILE LABS): FILE registers LABS (a program's labs) with the
# registry, from framework/app/register_labs.cpp.in; the desktop and the browser programs.
function(springlab_write_register file labs)
  set(register_calls "")
  set(register_includes "")
  foreach(name IN LISTS labs)
    string(APPEND register_includes "#include <springlab/${name}/${name}.hpp>\n")
    string(APPEND register_calls "  springlab::${name}::registerLab(registry);\n")
  endforeach()
  configure_file(${CMAKE_CURRENT_FUNCTION_LIST_DIR}/../framework/app/register_labs.cpp.in ${file} @ONLY)
endfunction()

# springlab_exercise_files(OUT LAB TREE): the paths of lab LAB's exercise files in TREE (labs or
# solutions), as its manifest lists them; with TREE = tests, their public test files, named after
# them (wind.cpp: tests/<dir>/public/wind_test.cpp). A listed file that is missing stops the
# configure, naming it and the manifest.
function(springlab_exercise_files out lab tree)
  set(dir ${SPRINGLAB_LAB_${lab}_DIR})
  set(paths "")
  foreach(file IN LISTS SPRINGLAB_LAB_${lab}_FILES)
    set(path ${tree}/${dir}/${file})
    if(tree STREQUAL "tests")
      string(REGEX REPLACE "[.]cpp$" "_test.cpp" test ${file})
      set(path tests/${dir}/public/${test})
    endif()
    if(NOT EXISTS ${CMAKE_SOURCE_DIR}/${path})
      message(FATAL_ERROR "${path}: missing, but tests/${dir}/exercises.json lists ${file} as an exercise's "
              "file (its public tests live in tests/${dir}/public/<file>_test.cpp)")
    endif()
    list(APPEND paths ${CMAKE_SOURCE_DIR}/${path})
  endforeach()
  set(${out} ${paths} PARENT_SCOPE)
endfunction()

# springlab_add_lab(NAME rope DIR 01_rope), once per lab of springlab_read_manifests()
#
# One lab is two parts: its given code, in framework/labs/<name>/ (the lab's system, scene
# reader, integrators and registration, with the headers that declare the exercises), and
# its exercises, one .cpp file each (the manifest's "file"s), in labs/<dir>/ (the student's)
# and solutions/<dir>/ (the reference). The given code calls the exercises through their declarations, so it is
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
    springlab_exercise_files(exercises ${LAB_NAME} ${folder})
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
    springlab_exercise_files(exercises ${LAB_NAME} solutions)
    add_library(springlab_${LAB_NAME}_solution_objects OBJECT ${exercises})
    target_link_libraries(springlab_${LAB_NAME}_solution_objects PUBLIC springlab_core PRIVATE springlab_warnings)
    target_include_directories(springlab_${LAB_NAME}_solution_objects PUBLIC ${given_dir}/include)
  endif()

  # What the grader links a submission's exercise objects with: the given objects.
  file(GENERATE OUTPUT ${CMAKE_BINARY_DIR}/grading/${LAB_NAME}_given_objects.txt
       CONTENT "$<JOIN:$<TARGET_OBJECTS:${given}>,\n>\n")
endfunction()
