# ctest script: install glintlab into a scratch prefix and import the installed Python package
# (PYTHONPATH at the prefix's site-packages) with the interpreter it was built for, evaluating a
# model once.
file(REMOVE_RECURSE "${WORK}")
execute_process(COMMAND "${CMAKE_COMMAND}" --install "${BUILD_DIR}" --prefix "${WORK}/prefix"
                RESULT_VARIABLE r OUTPUT_QUIET)
if(r)
  message(FATAL_ERROR "install failed: ${r}")
endif()
set(ENV{PYTHONPATH} "${WORK}/prefix/${SITE}")
execute_process(COMMAND "${PYTHON}" -c
  "import glintlab, os; assert glintlab.__file__.startswith(os.environ['PYTHONPATH']), glintlab.__file__; print(glintlab.eval('smooth_ggx', [0, 0, 1.0], [0, 0, 1.0])['value'])"
  RESULT_VARIABLE r)
if(r)
  message(FATAL_ERROR "import of the installed glintlab package failed: ${r}")
endif()
