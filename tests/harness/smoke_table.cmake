# CTest script: runs a smoke table (TABLE, default kitti360-standard) and compares it with the committed
# baseline (exit 4 from `sgnlf compare` = regression → test fails). The comparison is tight and
# --strict: a smoke table is compared only as a deterministic twin of its baseline (same configs;
# on another device or driver every metric must still match, else the report names both), and an
# improvement beyond the tight tolerance fails too (the baseline must be regenerated with the
# change that moved it). Runs of an earlier ctest are removed first: bench resumes finished
# runs, which would hide a change in training.
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
