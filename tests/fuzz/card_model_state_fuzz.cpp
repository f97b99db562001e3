// The trained card colour kept in the state folder (card-model.toml): any file is a model or one
// warning, and a model it gives is within the ranges the colour test divides by.
#include "firmware/card_model_store.hpp"
#include "fuzz_input.hpp"

#include <cstdlib>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    static const firmware::CardModelStore store(fuzz::scratchFolder());
    fuzz::writeScratchFile("card-model.toml", data, size);
    std::string warning;
    const auto model = store.load(warning);
    if (model)
        for (int i = 0; i < 3; ++i)
            if (!(model->sigma[i] >= 1.f && model->mean[i] >= 0.f && model->mean[i] <= 255.f))
                std::abort();
    return 0;
}
