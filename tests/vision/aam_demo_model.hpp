#pragma once
// The test and demo AAM model (scripts/dev model: out/aam/imm-demo.aam, built from research data
// that may be missing), loaded once per test program; tests that need it skip without it.

#include "test_paths.hpp"
#include "vision/aam_model.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <memory>
#include <string>

namespace aam_test {

/// The demo model, or nullptr when it is not built or does not load.
inline const vision::AamModel* demoModel()
{
    static std::unique_ptr<vision::AamModel> model = [] {
        const std::string path = testing_support::sourceDir() + "/out/aam/imm-demo.aam";
        if (!std::filesystem::exists(path))
            return std::unique_ptr<vision::AamModel>();
        vision::AamModelFile f = vision::loadAamModel(path);
        return f.ok ? std::make_unique<vision::AamModel>(std::move(f.model))
                    : std::unique_ptr<vision::AamModel>();
    }();
    return model.get();
}

}  // namespace aam_test

#define REQUIRE_DEMO_MODEL()              \
    if (aam_test::demoModel() == nullptr) \
    GTEST_SKIP() << "out/aam/imm-demo.aam is not built (scripts/dev model)"
