# Commands that write several files, killed with SIGKILL and run again (kill_resume_test.sh,
# docs/reliability.md#interruption); included by CMakeLists.txt. Each part has its own folder.
function(add_kill_resume_test part timeout)
  add_test(NAME cli.kill_resume.${part}
    COMMAND bash ${LH_CLI_SCRIPTS}/kill_resume_test.sh ${LH_CLI_EXE} ${CMAKE_CURRENT_BINARY_DIR}/kill_resume_${part}
            ${part})
  set_tests_properties(cli.kill_resume.${part} PROPERTIES TIMEOUT ${timeout} LABELS cli
    PASS_REGULAR_EXPRESSION "all cases passed")
endfunction()
add_kill_resume_test(synth 120)
add_kill_resume_test(export 120)
add_kill_resume_test(others 180)
if(TARGET lighthouse_net)  # predict and train run in lighthouse-net
  add_kill_resume_test(predict 240)
  add_kill_resume_test(train 240)
endif()
