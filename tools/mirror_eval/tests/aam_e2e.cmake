# End to end: mirror-eval aam on a few FGNet frames, a tiny headgen set and the IMM folder,
# checking the final lines' format (not the numbers: the full runs measure those), and that bad
# arguments are one line with exit code 2; with the demo model (scripts/dev model), the same on
# vision's fit (--fitter aam), which is not labelled a placeholder.
#   -DMIRROR_EVAL=... -DHEADGEN=... -DDATA=... -DOUT=... -DMODEL=...
file(REMOVE_RECURSE ${OUT})
file(MAKE_DIRECTORY ${OUT})
set(num "([0-9]+\\.[0-9]+|nan)")
set(fgnet ${DATA}/fgnet_talking_face)

function(run_eval pattern)
  execute_process(COMMAND ${MIRROR_EVAL} aam ${ARGN}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "mirror-eval aam ${ARGN} failed (${rc}): ${out}${err}")
  endif()
  string(STRIP "${out}" out)
  string(REGEX MATCH "[^\n]*$" last "${out}")
  if(NOT last MATCHES "${pattern}")
    message(FATAL_ERROR "unexpected final line '${last}' (expected '${pattern}') in:\n${out}")
  endif()
  if(NOT out MATCHES "PLACEHOLDER" AND NOT ARGN MATCHES "--fitter;aam")
    message(FATAL_ERROR "the placeholder runner is not labelled as one:\n${out}")
  endif()
  if(out MATCHES "PLACEHOLDER" AND ARGN MATCHES "--fitter;aam")
    message(FATAL_ERROR "the AAM fit is labelled a placeholder:\n${out}")
  endif()
  message(STATUS "${last}")
endfunction()

function(expect_usage_error pattern)
  execute_process(COMMAND ${MIRROR_EVAL} aam ${ARGN}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  string(STRIP "${err}" err)
  if(NOT rc EQUAL 2 OR NOT err MATCHES "^mirror-eval aam: ${pattern}" OR err MATCHES "\n")
    message(FATAL_ERROR "expected exit 2 and one line matching '${pattern}', got rc=${rc} "
                        "stderr='${err}' stdout='${out}'")
  endif()
endfunction()

run_eval("^aam: frames=3 nme=${num} nme_p90=${num} nme_all=${num} dlib_nme=${num} jaw_corr=${num} iters=${num} ms_per_frame=${num} lost=[0-9]+$"
         --frames ${fgnet}/images --truth ${fgnet}/points --max-frames 3 --data ${DATA})

execute_process(COMMAND ${HEADGEN} --out ${OUT}/heads --frames 3 --size 320x240 --hand some
                        --data ${DATA}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "headgen failed (${rc}): ${out}${err}")
endif()
run_eval("^aam-synthetic: frames=3 yaw_mae=${num} pitch_mae=${num} roll_mae=${num} anim_rmse=${num} hand_yaw_mae=${num} hand_pitch_mae=${num} hand_roll_mae=${num} nme=${num} dlib_nme=${num} lost=[0-9]+$"
         --synthetic ${OUT}/heads --data ${DATA})

run_eval("^aam-imm: images=30 type1_yaw=${num} type3_yaw=${num} type4_yaw=${num} sign_right=[0-9]+/[0-9]+$"
         --imm ${DATA}/imm_face_db --data ${DATA})

expect_usage_error("give one of --frames DIR --truth DIR, --synthetic DIR or --imm DIR")
expect_usage_error("--frames and --truth go together" --frames ${fgnet}/images)
expect_usage_error("give one of" --frames ${fgnet}/images --truth ${fgnet}/points --imm x)
expect_usage_error("--max-frames must be >= 0"
                   --frames ${fgnet}/images --truth ${fgnet}/points --max-frames -1)
expect_usage_error("unknown annotation scheme"
                   --frames ${fgnet}/images --truth ${fgnet}/points --scheme helen)
expect_usage_error("--start 1000: the sequence has only 1000 frames"
                   --frames ${fgnet}/images --truth ${fgnet}/points --start 1000)
expect_usage_error("--fitter aam needs --model FILE"
                   --frames ${fgnet}/images --truth ${fgnet}/points --fitter aam --data ${DATA})
if(EXISTS "${MODEL}")
  run_eval("^aam: frames=3 nme=${num} nme_p90=${num} nme_all=${num} dlib_nme=${num} jaw_corr=${num} iters=${num} ms_per_frame=${num} lost=[0-9]+$"
           --frames ${fgnet}/images --truth ${fgnet}/points --max-frames 3 --data ${DATA}
           --fitter aam --model ${MODEL})
endif()
expect_usage_error("--fitter magic: unknown"
                   --frames ${fgnet}/images --truth ${fgnet}/points --fitter magic --data ${DATA})
expect_usage_error(".*nowhere/frames: not a folder" --synthetic ${OUT}/nowhere)
# An option CLI11 does not know: one line, exit code 2 too.
execute_process(COMMAND ${MIRROR_EVAL} aam --bogus RESULT_VARIABLE rc ERROR_VARIABLE err)
string(STRIP "${err}" err)
if(NOT rc EQUAL 2 OR NOT err MATCHES "^mirror-eval: .*--bogus" OR err MATCHES "\n")
  message(FATAL_ERROR "an unknown option: expected exit 2 and one line, got rc=${rc} '${err}'")
endif()
