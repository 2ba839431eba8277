# CTest script: runs a smoke table (TABLE, default kitti360-standard) and compares it with the committed
# baseline (exit 4 from `sgnlf compare` = regression → test fails). With --strict: an improvement
# beyond the tolerance fails too (the baseline must be regenerated with the change that moved it).
# The configs must be the baseline's. On the baseline's device, driver and device profile the
# comparison is tight (a deterministic twin); on another device it is tight against that device's
# own baseline (devices/<slug>/results.json beside BASELINE) when there is one, else tight if
# every metric still matches and loose otherwise, the report saying that the device differs and
# has no baseline (so a GPU's first run fails only on what is not rounding: configs, rows, NaNs,
# metrics beyond the loose tolerances). Runs of an earlier ctest are removed first: bench resumes
# finished runs, which would hide a change in training.
if(NOT TABLE)
  set(TABLE kitti360-standard)
endif()
if(NOT EXISTS ${BASELINE})
  message(FATAL_ERROR "baseline ${BASELINE} is missing: make it with sgnlf bench --table ${TABLE} --scale smoke --seed 1")
endif()
file(REMOVE_RECURSE ${OUT}/runs)
execute_process(COMMAND ${SGNLF} bench --table ${TABLE} --scale smoke --seed 1 --out ${OUT}
                RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "sgnlf bench failed (exit ${rc})")
endif()
execute_process(COMMAND ${SGNLF} compare --strict ${OUT}/results.json ${BASELINE} RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "sgnlf compare found a regression against ${BASELINE} (exit ${rc})")
endif()
