# CTest script: the smoke table run as cells, each in its own `sgnlf bench --cell K` process,
# and merged (`sgnlf merge`) equals the one-process run: --expect ONE (the results.json of
# harness_smoke_table_low, the fixture this test requires) checks every field but times, paths
# and context (results/schema.md "Cells"), and `sgnlf compare --strict` against the committed
# baseline must pass. The checks are shown to bite: a merge with a cell left out must fail
# (exit 2) naming it, and a cell with a changed metric must make both checks fail (exit 4).
foreach(v SGNLF TABLE BASELINE ONE OUT)
  if(NOT DEFINED ${v})
    message(FATAL_ERROR "cells_table.cmake: -D${v}=... is required")
  endif()
endforeach()
if(NOT EXISTS ${ONE})
  message(FATAL_ERROR "the one-process result ${ONE} is missing (run the harness_smoke_table_low test)")
endif()
file(REMOVE_RECURSE ${OUT})
execute_process(COMMAND ${SGNLF} bench --table ${TABLE} --scale smoke --seed 1 --cells
                RESULT_VARIABLE rc OUTPUT_VARIABLE listing)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "sgnlf bench --cells failed (exit ${rc})")
endif()
string(REGEX MATCHALL "[^\n]+" lines "${listing}")
list(LENGTH lines n)
if(n LESS 2)
  message(FATAL_ERROR "sgnlf bench --cells listed ${n} cells:\n${listing}")
endif()
message(STATUS "${n} cells:\n${listing}")
set(dirs)
set(k 0)
foreach(line IN LISTS lines)
  if(NOT line MATCHES "^${k}\t")
    message(FATAL_ERROR "cell line ${k} does not start with its index: '${line}'")
  endif()
  execute_process(COMMAND ${SGNLF} bench --table ${TABLE} --scale smoke --seed 1 --cell ${k}
                          --out ${OUT}/cells/${k} RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "sgnlf bench --cell ${k} failed (exit ${rc})")
  endif()
  list(APPEND dirs ${OUT}/cells/${k})
  math(EXPR k "${k} + 1")
endforeach()

# A missing cell is refused, naming it.
list(SUBLIST dirs 0 ${k} all)
math(EXPR last "${n} - 1")
list(REMOVE_AT dirs ${last})
execute_process(COMMAND ${SGNLF} merge --out ${OUT}/partial ${dirs}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 2 OR NOT err MATCHES "1 of ${n} cells missing: ${last} ")
  message(FATAL_ERROR "a merge without cell ${last} was not refused (exit ${rc}):\n${out}${err}")
endif()

# All cells: equal to the one-process run, and a tight, strict match of the baseline.
execute_process(COMMAND ${SGNLF} merge --out ${OUT}/merged ${all} --expect ${ONE}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the merged cells differ from the one-process run ${ONE} (exit ${rc}):\n${out}")
endif()
message(STATUS "${out}")
execute_process(COMMAND ${SGNLF} compare --strict ${OUT}/merged/results.json ${BASELINE}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the merged table does not match ${BASELINE} (exit ${rc}):\n${out}")
endif()

# A cell whose metric changed: both checks must fail. The last cell (SG-NLF's): its CD is a
# number in the baseline (LiDAR4D's smoke cells, the first, predict no returns: CD null).
list(LENGTH all n_cells)
math(EXPR last "${n_cells} - 1")
list(GET all ${last} last_dir)
file(READ ${last_dir}/cell.json cell)
string(JSON cell SET "${cell}" outcome entry metrics cd "1000.0")
file(MAKE_DIRECTORY ${OUT}/tampered)
file(WRITE ${OUT}/tampered/cell.json "${cell}")
list(REMOVE_AT all ${last})
execute_process(COMMAND ${SGNLF} merge --out ${OUT}/merged-tampered ${OUT}/tampered ${all}
                        --expect ${ONE} RESULT_VARIABLE rc OUTPUT_VARIABLE out)
if(NOT rc EQUAL 4)
  message(FATAL_ERROR "a changed cell was not told apart from the one-process run (exit ${rc}):\n${out}")
endif()
execute_process(COMMAND ${SGNLF} compare --strict ${OUT}/merged-tampered/results.json ${BASELINE}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out)
if(NOT rc EQUAL 4)
  message(FATAL_ERROR "compare did not flag the changed cell (exit ${rc}):\n${out}")
endif()
message(STATUS "merged cells equal the one-process run; a missing and a changed cell are caught")
