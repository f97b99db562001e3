# End to end: one mirror-eval face sub-command on a small subset of the real data, checking the
# final line's format (not the numbers: the full runs measure those) and one-line errors.
#   -DWHICH=detect|roll|track_fgnet|track_composed|liveness -DMIRROR_EVAL=... -DDATA=... -DOUT=...
#   [-DFACEGEN=...] (track_composed)
file(REMOVE_RECURSE ${OUT})
file(MAKE_DIRECTORY ${OUT})
set(num "[0-9]+\\.[0-9]+")

function(run_eval pattern)
  execute_process(COMMAND ${MIRROR_EVAL} ${ARGN}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "mirror-eval ${ARGN} failed (${rc}): ${out}${err}")
  endif()
  string(STRIP "${out}" out)
  string(REGEX MATCH "[^\n]*$" last "${out}")
  if(NOT last MATCHES "${pattern}")
    message(FATAL_ERROR "unexpected final line '${last}' (expected '${pattern}') in:\n${out}")
  endif()
  message(STATUS "${last}")
endfunction()

function(expect_error name pattern)
  execute_process(COMMAND ${MIRROR_EVAL} ${ARGN}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  string(STRIP "${err}" err)
  if(rc EQUAL 0 OR NOT err MATCHES "${pattern}" OR err MATCHES "\n")
    message(FATAL_ERROR "${name}: expected one error line matching '${pattern}', got rc=${rc} "
                        "stderr='${err}' stdout='${out}'")
  endif()
endfunction()

set(cmu ${DATA}/cmu_mit_frontal)
set(fgnet ${DATA}/fgnet_talking_face)
if(WHICH STREQUAL "detect")
  # The small (320x240) CNN frames of set A keep this quick.
  file(STRINGS ${cmu}/landmarks_test_set_a.txt cnn REGEX "^cnn")
  list(JOIN cnn "\n" cnn)
  file(WRITE ${OUT}/cnn.txt "${cnn}\n")
  run_eval("^detect: precision=${num} recall=${num} agree_opencv=${num}$"
           detect --images ${cmu}/images --truth ${OUT}/cnn.txt --max-images 4)
  file(WRITE ${OUT}/bad.txt "voyager.png 1 2 3\n")
  expect_error(bad_truth "mirror-eval detect: .*bad.txt:1: expected 13 fields"
               detect --images ${cmu}/images --truth ${OUT}/bad.txt)
  file(WRITE ${OUT}/nope.txt "nope.png 1 2 3 4 5 6 7 8 9 10 11 12\n")
  expect_error(missing_image "mirror-eval detect: image .*nope.png: no such file"
               detect --images ${cmu}/images --truth ${OUT}/nope.txt)
  expect_error(missing_truth "mirror-eval detect: truth .*none.txt: cannot open"
               detect --images ${cmu}/images --truth ${OUT}/none.txt)
  expect_error(bad_cascade "mirror-eval detect: cascade .*"
               detect --images ${cmu}/images --truth ${cmu}/landmarks_test_set_a.txt
               --cascade ${OUT}/bad.txt)
elseif(WHICH STREQUAL "roll")
  run_eval("^roll: faces=[0-9]+ mean_err_deg=${num} within1=${num} within5=${num}$"
           roll --images ${cmu}/images --truth ${cmu}/landmarks_test_set_b.txt --rotate 30
           --seed 7 --max-faces 8)
  expect_error(bad_rotate "mirror-eval roll: --rotate must be in"
               roll --images ${cmu}/images --truth ${cmu}/landmarks_test_set_b.txt --rotate 120)
elseif(WHICH STREQUAL "track_fgnet")
  run_eval("^track: precision=${num} recall=${num} roll_mean_err_deg=${num}$"
           track --frames ${fgnet}/images --truth ${fgnet}/points --max-frames 8)
  run_eval("^track: precision=${num} recall=${num} roll_mean_err_deg=${num}$"
           track --frames ${fgnet}/images --truth ${fgnet}/points --start 990 --max-frames 4)
  expect_error(bad_start "mirror-eval track: --start 1000: the sequence has only 1000 frames"
               track --frames ${fgnet}/images --truth ${fgnet}/points --start 1000)
  expect_error(negative_start "mirror-eval track: --start must be >= 0"
               track --frames ${fgnet}/images --truth ${fgnet}/points --start -1)
  expect_error(bad_config "mirror-eval track: --config 'x'"
               track --frames ${fgnet}/images --truth ${fgnet}/points --config x)
  file(MAKE_DIRECTORY ${OUT}/empty)
  expect_error(no_truth "mirror-eval track: truth .*empty: no franck_00000.pts or"
               track --frames ${fgnet}/images --truth ${OUT}/empty)
elseif(WHICH STREQUAL "liveness")
  run_eval("^liveness: living_swayed_12=${num} moving_swayed_12=${num} static_swayed=${num} passed_swayed=${num}$"
           liveness --frames ${fgnet}/images --truth ${fgnet}/points --max-frames 30 --every 5)
  expect_error(bad_every "mirror-eval liveness: --every must be >= 1"
               liveness --frames ${fgnet}/images --truth ${fgnet}/points --every 0)
elseif(WHICH STREQUAL "track_composed")
  execute_process(COMMAND ${FACEGEN} --scenario two --frames 10 --size 320x240 --data ${DATA}
                          --out ${OUT}/seq
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "facegen failed (${rc}): ${out}${err}")
  endif()
  run_eval("^track: precision=${num} recall=${num} roll_mean_err_deg=${num}$"
           track --frames ${OUT}/seq/frames --truth ${OUT}/seq/truth --config similarity)
  file(WRITE ${OUT}/seq/truth/000003.txt "1 2 3\n")
  expect_error(bad_truth "mirror-eval track: .*000003.txt:1: expected 6 fields"
               track --frames ${OUT}/seq/frames --truth ${OUT}/seq/truth)
else()
  message(FATAL_ERROR "WHICH='${WHICH}'")
endif()
