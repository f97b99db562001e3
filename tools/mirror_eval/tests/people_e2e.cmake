# End to end: mirror-eval people on a few IMM persons and FGNet frames (seconds, not the full run:
# that measures the numbers, docs/people-evaluation.md), checking the final lines' format and that
# bad arguments are one line with exit code 2. Skips (passes, saying so) without the demo model.
#   -DMIRROR_EVAL=... -DDATA=... -DMODEL=... -DOUT=... [-DFACEGEN=...: a composed stranger too]
if(NOT EXISTS "${MODEL}")
  message(STATUS "SKIPPED: ${MODEL} is not built (scripts/dev model)")
  return()
endif()
set(num "([0-9]+\\.[0-9]+|nan)")
file(REMOVE_RECURSE ${OUT})
file(MAKE_DIRECTORY ${OUT})

set(stranger "")
if(FACEGEN)
  execute_process(COMMAND ${FACEGEN} --scenario one --frames 30 --out ${OUT}/stranger --data ${DATA}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "facegen failed (${rc}): ${out}${err}")
  endif()
  set(stranger --stranger ${OUT}/stranger)
endif()
execute_process(COMMAND ${MIRROR_EVAL} people --model ${MODEL} --data ${DATA} --persons 3
                        --max-frames 90 --enrol-frames 30 --window 30 --max-fits 15 ${stranger}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "mirror-eval people failed (${rc}): ${out}${err}")
endif()
string(STRIP "${out}" out)
string(REGEX MATCH "[^\n]*$" last "${out}")
if(NOT last MATCHES "^people: rank1=${num} rank1_turned=${num} false_accept=${num} fgnet_kept=${num}$")
  message(FATAL_ERROR "unexpected final line '${last}' in:\n${out}")
endif()
foreach(line "people-heldout: rank1=${num} rank1_turned=${num} false_accept=${num}\n"
             "cost per face: appearance parameters ${num} ms" "rank-1 \\(the nearest of the 3 enrolled")
  if(NOT out MATCHES "${line}")
    message(FATAL_ERROR "no line matching '${line}' in:\n${out}")
  endif()
endforeach()
if(FACEGEN AND NOT out MATCHES "people-stranger: not_franck=${num}\n")
  message(FATAL_ERROR "no people-stranger line in:\n${out}")
endif()
message(STATUS "${last}")

function(expect_usage_error pattern)
  execute_process(COMMAND ${MIRROR_EVAL} people ${ARGN}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  string(STRIP "${err}" err)
  if(NOT rc EQUAL 2 OR NOT err MATCHES "^mirror-eval( people)?: ${pattern}" OR err MATCHES "\n")
    message(FATAL_ERROR "expected exit 2 and one line matching '${pattern}', got rc=${rc} "
                        "stderr='${err}' stdout='${out}'")
  endif()
endfunction()
expect_usage_error(".*--model" --data ${DATA})
expect_usage_error("--enrol 3: give 1 or 1,2" --model ${MODEL} --data ${DATA} --enrol 3)
expect_usage_error("--persons must be 2-40" --model ${MODEL} --data ${DATA} --persons 1)
expect_usage_error("--imm .*nowhere: not a folder" --model ${MODEL} --imm ${DATA}/nowhere)
expect_usage_error(".*--window and --max-fits must be >= 1" --model ${MODEL} --data ${DATA} --window 0)
expect_usage_error("--stranger needs the FGNet run" --model ${MODEL} --data ${DATA} --persons 2
                   --frames none --stranger ${OUT})
expect_usage_error("--truth .*nowhere: not a folder" --model ${MODEL} --data ${DATA}
                   --frames ${DATA}/fgnet_talking_face/images --truth ${DATA}/nowhere)
