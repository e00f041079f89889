"""The springlab grader: grades students' exercise files against this instructor tree.

Modules, one concern each (the command-line front ends are tools/grade.py, tools/submission.py
and tools/autograder.py):

    errors        GradeError: bad input or a broken instructor tree
    manifest      a lab's tests/<dir>/exercises.json (points, visibility) and its handout
    labs          the labs of this tree: one manifest each (tests/<dir>/exercises.json)
    failures      what a failed or crashed test says: signal names, GoogleTest's text cleaned
    sandbox       limits, user and process group of one untrusted process
    staging       copies of what the sandbox users read or run, outside the instructor's checkout
    sealed_compile the compiler in bubblewrap: the toolchain, staged headers, the submission only
    call_check    the calls exercise code may not make (shared by `grade` and `check`)
    student_check `check`'s call check of a student's own build
    platforms     PrairieLearn's results.json, GitHub Classroom's autograding result
    gtest_runner  listing and running a grading program's tests, the private result channel
    results       what grading found: per test, per lab, per submission
    reports       report.md, Gradescope results.json, junit.xml, gradebook.csv, the terminal
    build_cache   the instructor build: compile flags, the CMake-written link, object cache
    submission    a submission's shape: zip extraction, lab folders, exercise files
    integrity     checks of compiled exercise files: includes, calls and symbols that cheat
    lab_grader    one lab of one submission (compile, check, link, run) and whole classes
    gradescope    the Gradescope autograder bundle (setup.sh, run_autograder)
"""
