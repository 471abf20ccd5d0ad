# `--shard K/N` and `lighthouse merge` (included by CMakeLists.txt): bad shard specifications
# and merges of nothing are one clear error; tests/shard/shard_test.sh checks that two shards
# and a merge write what one run writes (synth; with the network, batch predict and eval too).

lighthouse_cli_error(synth_shard_out_of_range
  EXPECT "--shard must be K/N with 0 <= K < N.*got '5/4'"
  ABSENT syn_shard_bad
  ARGS synth -o syn_shard_bad --count 2 --shard 5/4)
lighthouse_cli_error(synth_shard_not_a_fraction
  EXPECT "--shard must be K/N.*got 'x'"
  ABSENT syn_shard_bad
  ARGS synth -o syn_shard_bad --count 2 --shard x)
lighthouse_cli_error(synth_shard_of_zero
  EXPECT "--shard must be K/N.*got '0/0'"
  ABSENT syn_shard_bad
  ARGS synth -o syn_shard_bad --count 2 --shard 0/0)
lighthouse_cli_error(merge_without_shard_records
  EXPECT "'adir' holds no shard records"
  ARGS merge adir)
lighthouse_cli_error(merge_missing_directory
  EXPECT "'no_such_dir' is not a directory"
  ARGS merge no_such_dir)
lighthouse_cli_ok(help_merge
  STDOUT "Usage:.*merge" "incomplete set" "merged"
  ARGS merge --help)

if(TARGET lighthouse_net)
  lighthouse_cli_error(predict_shard_needs_the_batch_form
    EXPECT "--shard needs the batch form"
    ABSENT pred_shard_bad.vdb
    MAX_MEMORY_MB ${LH_TORCH_MB}
    ARGS predict ${LH_PAIR_ARGS} --cameras ${LH_PAIR}/cameras.json --shard 0/2 -o pred_shard_bad.vdb)
  lighthouse_cli_error(predict_batch_output_is_a_directory
    EXPECT "-o is a directory"
    ABSENT pred_batch_bad.vdb
    MAX_MEMORY_MB ${LH_TORCH_MB}
    ARGS predict --examples adir -o pred_batch_bad.vdb)
  lighthouse_cli_error(predict_batch_missing_list
    EXPECT "cannot read the list of pairs 'no_such_list[.]txt'"
    MAX_MEMORY_MB ${LH_TORCH_MB}
    ARGS predict --pairs no_such_list.txt -o pred_batch_bad)
  lighthouse_cli_error(eval_shard_out_of_range
    EXPECT "--shard must be K/N.*got '2/2'"
    MAX_MEMORY_MB ${LH_TORCH_MB}
    ARGS eval --data adir --shard 2/2 -o eval_shard_bad)
  set(LH_SHARD_NET --net)
endif()
add_test(NAME cli.shard.two_shards_and_merge_write_what_one_run_writes
  COMMAND bash ${PROJECT_SOURCE_DIR}/tests/shard/shard_test.sh ${LH_CLI_EXE} ${LH_CLI_WORK}/shard ${LH_SHARD_NET})
lighthouse_cli_properties(cli.shard.two_shards_and_merge_write_what_one_run_writes)
set_tests_properties(cli.shard.two_shards_and_merge_write_what_one_run_writes PROPERTIES TIMEOUT 600)
