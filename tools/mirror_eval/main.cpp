// mirror-eval: evaluates the vision core on recorded or generated sequences with ground truth.
// One sub-command per tracker: `card` now; later issues add `detect`, `roll`, `track`.

#include "card_eval.hpp"

#include <CLI/CLI.hpp>
#include <cstdio>

int main(int argc, char** argv)
{
    CLI::App app{"mirror-eval: scores the vision core against ground truth"};
    app.require_subcommand(1);

    mirror_eval::CardEvalOptions card;
    CLI::App* cardCmd =
        app.add_subcommand("card",
                           "the colour-card tracker on a video or frame folder with a truth CSV "
                           "(frame,x0,y0,x1,y1,x2,y2,x3,y3; empty corners = no card)");
    cardCmd->add_option("--video", card.video, "video file or folder of frames")->required();
    cardCmd->add_option("--truth", card.truth, "truth CSV, one row per frame")->required();
    cardCmd
        ->add_option("--train-fraction", card.trainFraction,
                     "central fraction of frame 0 that trains the colour model")
        ->capture_default_str();
    cardCmd->add_flag("--deinterlace", card.deinterlace,
                      "deinterlace first (the firmware's vision.deinterlace = true)");
    cardCmd->add_option("--per-frame", card.perFrameCsv,
                        "also write the tracker's per-frame corners and errors to this CSV");

    CLI11_PARSE(app, argc, argv);
    if (cardCmd->parsed())
        return mirror_eval::runCardEval(card, stdout, stderr);
    return 2;
}
