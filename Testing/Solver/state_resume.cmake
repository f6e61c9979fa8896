# Exact resume in a fresh process: A runs 2N steps in one process; B runs N steps, saves,
# and a NEW process loads the file and runs N more. A and B must be bitwise identical.
# Usage: cmake -DEXE=... -DSPECIMEN=settling|cemented|triaxial|membrane -DSTEPS=N -DDIR=... -P state_resume.cmake
file(MAKE_DIRECTORY "${DIR}")
math(EXPR TWICE "2 * ${STEPS}")
foreach(step
    "start;${SPECIMEN};${TWICE};${DIR}/a.rdem"
    "start;${SPECIMEN};${STEPS};${DIR}/b_half.rdem"
    "continue;${DIR}/b_half.rdem;${STEPS};${DIR}/b.rdem"
    "compare;${DIR}/a.rdem;${DIR}/b.rdem")
  execute_process(COMMAND "${EXE}" ${step} RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "rockdem_state_resume ${step} failed (${rc})")
  endif()
endforeach()
file(REMOVE_RECURSE "${DIR}")
