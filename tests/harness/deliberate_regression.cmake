# CTest script: the CI comparison catches what it claims to catch. The committed baseline
# compared with itself (tight, --strict) must pass; each of these copies must make
# `sgnlf compare --strict` exit with 4 (regression):
#   worse     the first running row's mean Chamfer distance set to 1000 m² (CMake has no float math)
#   improved  the same set to 0: better beyond the tight tolerance means a stale baseline
#   device    another OpenCL device and a worse CD: a smoke table stays under the tight
#             tolerances there, and the report names both devices (before: silently loose, CD ±25 %)
#   config    another config hash in a sequence: not a twin either
file(READ ${BASELINE} base)
string(JSON n LENGTH "${base}" rows)
math(EXPR last "${n} - 1")
set(row -1)
foreach(i RANGE ${last})
  string(JSON status GET "${base}" rows ${i} status)
  if(status STREQUAL "ok" AND row EQUAL -1)
    set(row ${i})
  endif()
endforeach()
if(row EQUAL -1)
  message(FATAL_ERROR "baseline ${BASELINE} has no row with status ok")
endif()
file(MAKE_DIRECTORY ${OUT})
execute_process(COMMAND ${SGNLF} compare --strict ${BASELINE} ${BASELINE} RESULT_VARIABLE rc_same)
if(NOT rc_same EQUAL 0)
  message(FATAL_ERROR "the baseline compared with itself did not pass (exit ${rc_same})")
endif()

string(JSON worse SET "${base}" rows ${row} mean cd "1000.0")
string(JSON improved SET "${base}" rows ${row} mean cd "0.0")
string(JSON same_numbers SET "${base}" context opencl device "\"another OpenCL device\"")
string(JSON device SET "${same_numbers}" rows ${row} mean cd "1000.0")
string(JSON config SET "${base}" rows ${row} sequences 0 config_hash "\"0000000000000000\"")
foreach(kind worse improved device config)
  file(WRITE ${OUT}/${kind}.json "${${kind}}")
  execute_process(COMMAND ${SGNLF} compare --strict ${OUT}/${kind}.json ${BASELINE}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out)
  if(NOT rc EQUAL 4)
    message(FATAL_ERROR "the '${kind}' copy of the baseline was not flagged (exit ${rc}, expected 4):\n${out}")
  endif()
  message(STATUS "'${kind}' copy flagged (exit 4), as it must be")
endforeach()
# The device mismatch names both devices and says what to do.
execute_process(COMMAND ${SGNLF} compare ${OUT}/device.json ${BASELINE} RESULT_VARIABLE rc OUTPUT_VARIABLE out)
if(NOT rc EQUAL 4 OR NOT out MATCHES "another OpenCL device" OR NOT out MATCHES "regenerate the baseline")
  message(FATAL_ERROR "a device mismatch did not fail with a clear message (exit ${rc}):\n${out}")
endif()
# Another device that computes the same numbers (another PoCL CPU target) passes, tight, with a
# note naming both devices.
file(WRITE ${OUT}/same_numbers.json "${same_numbers}")
execute_process(COMMAND ${SGNLF} compare --strict ${OUT}/same_numbers.json ${BASELINE}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out)
if(NOT rc EQUAL 0 OR NOT out MATCHES "tight tolerances" OR NOT out MATCHES "another OpenCL device")
  message(FATAL_ERROR "another device with the same numbers did not pass tight with a note (exit ${rc}):\n${out}")
endif()
