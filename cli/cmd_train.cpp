// `lighthouse train --data DIR [--config standard] -o model.pt [--checkpoint PATH] [--init MODEL]
// [--half]` Data-parallel: `[--batch B] --world-size N --rank R --master HOST:PORT`, or torchrun's
// or srun's variables (net/distributed.h, docs/distributed.md).
#include "cli/commands.h"
#include "cli/common_options.h"
#include "cli/net_commands.h"
#include "net/trainer.h"

#include <iostream>

namespace lh::cli {

void addTrainCommand(CLI::App& app, const int& threads) {
    auto o = std::make_shared<net::TrainOptions>();
    CLI::App* cmd = app.add_subcommand("train", netCommandDescription("train"));
    cmd->add_option("--data", o->data, "Training split written by `lighthouse synth --split train`")
        ->required();
    cmd->add_option("--val", o->validation,
                    "Held-out scenes for validation (default: the last 5% of --data)");
    cmd->add_option("--max-clipped", o->maxClipped,
                    "Leave out scenes of --data with an envmap whose pixels are above 1 (white on "
                    "a display) over more than this fraction of it, before the held-out split; "
                    "0.1: no more than the path-traced evaluation rooms clip (1: keep all)")
        ->capture_default_str();
    cmd->add_option("--max-photo-clipped", o->maxPhotoClipped,
                    "Lower each example's exposure until at most this fraction of its reference "
                    "photo clips, as a camera metering for its highlights does (uses the views' "
                    "unclipped EXRs; `lighthouse photo-clipping` shows what then clips; 1: the "
                    "exposure as drawn)")
        ->capture_default_str();
    cmd->add_option(
           "--config", o->config,
           "standard (5 x 64^3 from 192x144, 32 planes, HDR), wide (standard with completion "
           "networks twice as wide), paper, or small; a '+profile' suffix (wide+profile) also "
           "gives the completion networks the observed colour at each height of the room, and "
           "'+emitters' (wide+emitters) adds a head that places 3 compact lamps in the volume, "
           "'+photo' with it (wide+emitters+photo) a head that also reads the photo and puts "
           "each lamp at the peak of its distribution over places, '+cells' with both a "
           "classifier of where lamps are from the photo alone (see --pretrain-lamp-cells), "
           "'+apart' with '+photo' lamps that each take a different peak, and '+unclipped' "
           "with '+photo' a head that reads the photo before its clip at 1 (the examples' EXR "
           "renders; at predict, an EXR photo)")
        ->capture_default_str();
    cmd->add_option("-o,--output", o->out,
                    "Model file OUT; OUT.csv and OUT.png (training curves) are written next to it")
        ->capture_default_str();
    cmd->add_option("--checkpoint", o->checkpoint,
                    "Resumable training state, written atomically (default: OUT.checkpoint); keep "
                    "it outside the "
                    "repository so that a run can span sittings");
    cmd->add_option("--init", o->init,
                    "When no checkpoint exists: fine-tune from this model (same configuration) "
                    "with a fresh optimiser");
    cmd->add_flag("--init-partial", o->initPartial,
                  "With --init of another configuration: start from its parameters wherever name "
                  "and shape match (a standard model's MPI network for --config wide; all of a "
                  "wide model for wide+profile, the new inputs zero-weighted; all but the "
                  "emitter head for wide+emitters), the rest fresh");
    cmd->add_flag("--init-widen", o->initWiden,
                  "With --init of a model whose completion networks are half as wide (standard "
                  "for --config wide): start from the same predictions, each channel split in two");
    cmd->add_option("--supervision", o->supervision,
                    "direct: also the oracle volume (oracle.vdb, synth --oracle-levels) and the "
                    "reference depth; "
                    "paper: rendered views and envmaps only, the paper's staged schedule")
        ->capture_default_str();
    cmd->add_option("--stop-after", o->stopAfter,
                    "End this sitting after N iterations, checkpointed; the same command resumes "
                    "(0: run to the end)")
        ->capture_default_str();
    o->halfModel = false;  // float32 unless --half, as every command that writes values
    addHalfFlag(cmd, o->halfModel,
                "Write OUT in 16-bit halves instead of float32 (half the size; the checkpoint "
                "stays float32)");
    cmd->add_flag("!--no-augment", o->augment, "No exposure, white-balance and noise augmentation");
    cmd->add_option("--iterations", o->iterations,
                    "Training iterations (optimiser steps, of --batch examples each)")
        ->capture_default_str();
    cmd->add_option("--lr", o->learningRate, "Adam learning rate (divided by 10 for the last 20%)")
        ->capture_default_str();
    cmd->add_option("--average-decay", o->averageDecay,
                    "The model written and validated is the moving average of the weights with "
                    "this decay per "
                    "iteration (0: the last step's weights)")
        ->capture_default_str();
    cmd->add_option("--irradiance-weight", o->irradianceWeight,
                    "Weight of the diffuse-irradiance loss (the light each axis-facing diffuse "
                    "patch receives) beside the per-pixel envmap losses")
        ->capture_default_str();
    cmd->add_option("--irradiance-focus", o->irradianceFocus,
                    "Where the irradiance loss asks for light: 0 from every envmap pixel alike, 1 "
                    "from each in proportion to its predicted brightness (the lamps and windows "
                    "the model already predicts), higher more so")
        ->capture_default_str();
    cmd->add_option("--envmap-mse-weight", o->envmapSquaredWeight,
                    "Weight of the squared sRGB error of envmaps (what PSNR scores) beside the L1 "
                    "losses; 0: off")
        ->capture_default_str();
    cmd->add_option("--highlight-weight", o->highlightWeight,
                    "Weight of the highlight loss on envmaps: the lamps and windows the photo saw "
                    "at least twice as bright as white (or as bright as they are), nothing else "
                    "above white, as a mirror ball shows them; needs each envmap's observed mask "
                    "(env_K_mask.png, or env_K_pos.exr and the reference depth); 0: off")
        ->capture_default_str();
    cmd->add_option("--coarse-envmap-weight", o->coarseEnvmapWeight,
                    "Weight of the HDR loss (log radiance) of envmaps averaged over blocks "
                    "(--coarse-envmap-block): asks for the light of each block however it is "
                    "spread inside it, so a lamp the volume can only show spread over a voxel "
                    "may be as bright as it is; 0: off")
        ->capture_default_str();
    cmd->add_option("--coarse-envmap-block", o->coarseEnvmapBlock,
                    "Side of the coarse HDR loss's blocks in envmap pixels (4: 12 degrees of a "
                    "120x60 envmap); larger blocks also forgive a lamp placed a little off")
        ->capture_default_str();
    cmd->add_option("--view-hdr-weight", o->viewHdrWeight,
                    "Weight of the HDR loss (log radiance) of the MPI's held-out view against its "
                    "unclipped render tgt.exr: it teaches how bright clipped windows and lamps "
                    "are; 0: off")
        ->capture_default_str();
    cmd->add_option("--prune-alpha", o->pruneAlpha,
                    "Train under pruning: render the envmaps with voxels of alpha below this left "
                    "empty (gradients straight through), so the model learns opaque walls and "
                    "empty rooms; the model records it and predict prunes there by default; "
                    "0: off")
        ->capture_default_str();
    cmd->add_option("--highlight-gain", o->highlightGain,
                    "Train under a highlight gain: every loss sees the completed volume with what "
                    "each voxel holds above white multiplied by this, as predict --highlight-gain "
                    "exports it; the model records it and predict applies it by default; 1: off")
        ->capture_default_str();
    cmd->add_option("--direct-adversarial-weight", o->directAdversarialWeight,
                    "Weight of the paper's PatchGAN loss on the envmaps under direct supervision, "
                    "from the first step: it asks for envmaps that look like rooms (lamps and "
                    "windows) where the per-pixel losses settle for a blur; 0: off")
        ->capture_default_str();
    cmd->add_option("--adversarial-input", o->adversarialInput,
                    "What the PatchGAN discriminator sees of an envmap: srgb (clamped at 1, the "
                    "paper's) or log (ln(1 + radiance): a lamp is brighter than a white wall)")
        ->capture_default_str();
    cmd->add_option("--alpha-binary-weight", o->alphaBinaryWeight,
                    "Weight of the prior towards empty or opaque voxels (the mean of alpha (1 - "
                    "alpha)); with --prune-alpha it asks for empty rooms and opaque walls, which "
                    "render fastest; 0: off")
        ->capture_default_str();
    cmd->add_option("--emitter-position-weight", o->emitterPositionWeight,
                    "With an emitter head (--config wide+emitters): weight of the squared "
                    "distance (m^2) from each of its lamps to the nearest lamp or window of the "
                    "example's scene.json; 0: off")
        ->capture_default_str();
    cmd->add_option("--emitter-cell-weight", o->emitterCellWeight,
                    "With an emitter head (best --config wide+emitters+photo): weight of the "
                    "divergence (nats) of its distribution over level 0's cells from the cells "
                    "of the example's true lamps and windows (scene.json); 0: off")
        ->capture_default_str();
    cmd->add_flag("--lamp-cells-unseen", o->lampCellsUnseenOnly,
                  "The lamp cells (of --emitter-cell-weight and --pretrain-lamp-cells) name only "
                  "the lamps and windows the reference photo does not show (centre behind the "
                  "camera or outside the image)");
    cmd->add_option("--emitter-light-weight", o->emitterLightWeight,
                    "With an emitter head: weight of the error of the irradiance its lamps send "
                    "to each training envmap's point (per colour, on the six axis normals, as "
                    "predict prunes them) against that of the envmap's unobserved pixels above "
                    "luminance 1 (the lamps and windows the photo did not see): the log of the "
                    "ratio short of it, the ratio less 1 beyond; it trains their radiance and "
                    "opacity; 0: off")
        ->capture_default_str();
    cmd->add_option("--pretrain-lamp-cells", o->pretrainLampCellEpochs,
                    "With --config ...+emitters+photo+cells: epochs of training the head's "
                    "photo classifier of where lamps are on the training photos alone, before "
                    "the first step (scored on the held-out scenes in the log); 0: none")
        ->capture_default_str();
    cmd->add_option("--closure-weight", o->closureWeight,
                    "Weight of the closed-room prior (the mean transmittance an envmap ray has "
                    "left behind the volume): asks for walls that stop every ray, as the "
                    "training rooms' do, instead of fog that lets rays out; 0: off")
        ->capture_default_str();
    cmd->add_option("--validate-every", o->validateEvery, "Iterations between validations")
        ->capture_default_str();
    cmd->add_option("--validation-scenes", o->validationScenes,
                    "Held-out scenes scored at each validation")
        ->capture_default_str();
    cmd->add_option("--checkpoint-every", o->checkpointEvery, "Iterations between checkpoints")
        ->capture_default_str();
    cmd->add_option("--log-every", o->logEvery, "Iterations between progress lines")
        ->capture_default_str();
    cmd->add_option("--seed", o->seed, "Random seed")->capture_default_str();
    cmd->add_option("--device", o->device,
                    "cpu, or cuda with a CUDA build of libtorch (not yet tested on a GPU)")
        ->capture_default_str();
    cmd->add_option("--vgg", o->vggWeights,
                    "VGG-19 weights for the paper's perceptual loss (TorchScript; see "
                    "net/vgg_loss.h); default: L1 + gradients");
    cmd->add_flag("!--no-resume", o->resume, "Start afresh even if the checkpoint exists");
    cmd->add_option("--batch", o->batch,
                    "Examples per iteration over all ranks (the gradient is their mean); a "
                    "multiple of --world-size")
        ->capture_default_str();
    auto dist = std::make_shared<net::DistributedFlags>();
    cmd->add_option(
        "--world-size", dist->worldSize,
        "Data-parallel: number of processes (default: WORLD_SIZE, or srun's task count, or 1)");
    cmd->add_option(
        "--rank", dist->rank,
        "Data-parallel: this process, 0 .. world size - 1 (default: RANK or SLURM_PROCID)");
    cmd->add_option("--master", dist->master,
                    "Data-parallel: HOST:PORT of rank 0, which serves the rendezvous (default: "
                    "MASTER_ADDR:MASTER_PORT)");
    cmd->add_option("--dist-timeout", dist->timeoutSeconds,
                    "Data-parallel: seconds to wait for the rendezvous and for any collective "
                    "before failing")
        ->capture_default_str();
    cmd->add_option("--dist-backend", dist->backend,
                    "Data-parallel: gloo (CPU), or nccl with --device cuda in a CUDA build "
                    "(docs/distributed.md)")
        ->capture_default_str();
    cmd->callback([o, dist, &threads] {
        o->threads = threads;
        o->distributed = net::resolveDistributed(*dist);
        net::train(*o, std::cerr);
    });
}

}  // namespace lh::cli
