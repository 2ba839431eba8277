# CTest script: the CI comparison catches what it claims to catch. The committed baseline
# compared with itself (tight, --strict) must pass; each of these copies must make
# `sgnlf compare --strict` exit with 4 (regression):
#   worse     the first running row's mean Chamfer distance set to 1000 m²
#   improved  the same set to 0: better beyond the tight tolerance means a stale baseline
#   device    another OpenCL device and that CD of 1000 m²: beyond even the loose tolerances
#             that another device without a baseline of its own gets, and the report says so
#   config    another config hash in a sequence: not a twin, on any device
# and the per-device baselines work (runtime/harness/device_baseline.hpp): another device whose
# CD is 1 % worse passes loosely with a note naming the device and where its own baseline goes;
# with that device's own baseline there (a copy of its run), the same result fails tightly and
# the device's own numbers pass.
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
if(NOT rc EQUAL 4 OR NOT out MATCHES "another OpenCL device" OR NOT out MATCHES "no baseline of this device exists")
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

# Per-device baselines, on a copy of the baseline's folder. The CD 1 % worse (fixed-point
# integer math on its decimal digits: CMake has no float math).
string(JSON cd GET "${base}" rows ${row} mean cd)
if(NOT cd MATCHES "^([0-9]+)\\.([0-9]+)$")
  message(FATAL_ERROR "the baseline's mean CD '${cd}' is not a plain decimal")
endif()
set(int_part ${CMAKE_MATCH_1})
string(SUBSTRING "${CMAKE_MATCH_2}000000" 0 6 frac)
string(REGEX REPLACE "^0+([0-9])" "\\1" frac_num "${frac}")
math(EXPR micro "(${int_part} * 1000000 + ${frac_num}) * 101 / 100")
math(EXPR worse_int "${micro} / 1000000")
math(EXPR worse_frac "${micro} % 1000000 + 1000000")
string(SUBSTRING "${worse_frac}" 1 6 worse_frac)
string(JSON drift SET "${same_numbers}" rows ${row} mean cd "${worse_int}.${worse_frac}")
file(WRITE ${OUT}/device_drift.json "${drift}")
file(REMOVE_RECURSE ${OUT}/tables)
file(MAKE_DIRECTORY ${OUT}/tables/smoke)
file(WRITE ${OUT}/tables/smoke/results.json "${base}")
execute_process(COMMAND ${SGNLF} compare --strict ${OUT}/device_drift.json ${OUT}/tables/smoke/results.json
                RESULT_VARIABLE rc OUTPUT_VARIABLE out)
if(NOT rc EQUAL 0 OR NOT out MATCHES "loose tolerances" OR NOT out MATCHES "another OpenCL device"
   OR NOT out MATCHES "no baseline of this device exists"
   OR NOT out MATCHES "copy this run's results.json to ([^ ]+/devices/[^ ]+/results.json)")
  message(FATAL_ERROR "another device 1 % off without its own baseline did not pass loosely with a note (exit ${rc}):\n${out}")
endif()
set(own ${CMAKE_MATCH_1})
message(STATUS "another device without its own baseline: loose, passes, names ${own}")
file(WRITE ${own} "${same_numbers}")  # that device's own run, as results/README.md says
execute_process(COMMAND ${SGNLF} compare --strict ${OUT}/device_drift.json ${OUT}/tables/smoke/results.json
                RESULT_VARIABLE rc OUTPUT_VARIABLE out)
if(NOT rc EQUAL 4 OR NOT out MATCHES "this device's own" OR NOT out MATCHES "tight tolerances")
  message(FATAL_ERROR "another device 1 % off its own baseline was not flagged tightly (exit ${rc}):\n${out}")
endif()
execute_process(COMMAND ${SGNLF} compare --strict ${OUT}/same_numbers.json ${OUT}/tables/smoke/results.json
                RESULT_VARIABLE rc OUTPUT_VARIABLE out)
if(NOT rc EQUAL 0 OR NOT out MATCHES "this device's own")
  message(FATAL_ERROR "another device's rerun did not pass against its own baseline (exit ${rc}):\n${out}")
endif()
message(STATUS "with its own baseline: tight, the 1 % drift flagged (exit 4), its own numbers pass")
