# End-to-end: cardgen renders a short sequence; mirror-eval card runs the tracker on it and prints
# its final line. Also its one-line errors: missing video, missing truth, malformed truth, frame
# count mismatch. Accuracy is not asserted here (the tracker's own tests and the full-length runs
# do that).
file(REMOVE_RECURSE ${OUT})
execute_process(COMMAND ${CARDGEN} --scenario perspective --frames 12 --size 360x240
                        --data ${DATA} --out ${OUT}/seq
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "cardgen failed (${rc}): ${out}${err}")
endif()

execute_process(COMMAND ${MIRROR_EVAL} card --video ${OUT}/seq --truth ${OUT}/seq/truth.csv
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "mirror-eval card failed (${rc}): ${out}${err}")
endif()
string(STRIP "${out}" out)
string(REGEX MATCH "[^\n]*$" last "${out}")
if(NOT last MATCHES "^card: mean_err_px=[-0-9.naif]+ p95_err_px=[-0-9.naif]+ within3px=[-0-9.naif]+ lost_frames=[0-9]+")
  message(FATAL_ERROR "unexpected final line '${last}' in:\n${out}")
endif()

function(expect_error name pattern)
  execute_process(COMMAND ${MIRROR_EVAL} card ${ARGN}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  string(STRIP "${err}" err)
  if(rc EQUAL 0 OR NOT err MATCHES "${pattern}" OR err MATCHES "\n")
    message(FATAL_ERROR "${name}: expected one error line matching '${pattern}', got rc=${rc} "
                        "stderr='${err}' stdout='${out}'")
  endif()
endfunction()

expect_error(missing_video "no such file" --video ${OUT}/nope --truth ${OUT}/seq/truth.csv)
expect_error(missing_truth "truth .*nope.csv: cannot open" --video ${OUT}/seq --truth ${OUT}/nope.csv)
file(WRITE ${OUT}/bad.csv "frame,x0,y0,x1,y1,x2,y2,x3,y3\n0,1,2,3,4,5,6,7,8\n1,1,2,3,x,5,6,7,8\n")
expect_error(malformed_truth "bad.csv:3: y1 'x' is not a number" --video ${OUT}/seq --truth ${OUT}/bad.csv)
file(WRITE ${OUT}/short.csv "frame,x0,y0,x1,y1,x2,y2,x3,y3\n0,1,2,3,4,5,6,7,8\n1,,,,,,,,\n")
expect_error(frame_count "frame count mismatch: .* has 12 frames, .*short.csv has 2 rows" --video ${OUT}/seq --truth ${OUT}/short.csv)
