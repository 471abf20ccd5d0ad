# `lighthouse eval-diff`: the paired difference of the fixture's two evals (B's PSNR up 1, 0.5
# and 2 dB: mean 7/6, standard error sqrt(7/36)), from their folders or their metrics.csv, and
# one error line for a missing eval, a folder without metrics.csv, a file that is no eval's,
# and a method neither scored.
lighthouse_cli_ok(eval_diff_folders
  STDOUT "[|] psnr_all_db [|] 3 [|] [+]1[.]1667 [|] 0[.]4410 [|] B better [|]"
         "[|] irradiance_rel_error [|] 3 [|] [+]0[.]0000 [|] 0[.]0000 [|] the same on every envmap [|]"
         "[|] highlight_precision [|] 0 [|]"
  ARGS eval-diff eval_a eval_b)
lighthouse_cli_ok(eval_diff_files
  STDOUT "[|] psnr_all_db [|] 3 [|] -1[.]1667 [|] 0[.]4410 [|] B worse [|]"
  ARGS eval-diff eval_b/metrics.csv eval_a/metrics.csv)
lighthouse_cli_error(eval_diff_missing
  EXPECT "no_such_eval.*does not exist"
  ARGS eval-diff eval_a no_such_eval)
lighthouse_cli_error(eval_diff_no_metrics
  EXPECT "holds no metrics[.]csv"
  ARGS eval-diff eval_a .)
lighthouse_cli_error(eval_diff_not_an_eval
  EXPECT "cameras_ok[.]json.*not an eval's metrics[.]csv"
  ARGS eval-diff eval_a cameras_ok.json)
lighthouse_cli_error(eval_diff_unknown_method
  EXPECT "no envmap of method 'oracle'.*'ours'"
  ARGS eval-diff eval_a eval_b --method oracle)
