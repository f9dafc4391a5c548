// GPU test fixture: one validated Vulkan context for the whole run (lavapipe in CI); any
// validation message during a test fails that test.
#pragma once

#include <gtest/gtest.h>

#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "gpu/context.h"
#include "scansurf/engine.h"

namespace scansurf::test {

// Options that route validation messages into the fixture's log.
EngineOptions validatedEngineOptions();
// Adds a validation message to the running test's log (which fails the test at TearDown).
void recordValidationMessage(std::string_view message);
gpu::Context& sharedContext();

class GpuTest : public ::testing::Test {
 protected:
  void SetUp() override;
  void TearDown() override;
};

// A GpuTest whose suite shares one validated Engine, created before its first test.
class EngineTest : public GpuTest {
 protected:
  static void SetUpTestSuite() {
    auto engine = Engine::create(validatedEngineOptions());
    ASSERT_TRUE(engine) << engine.error().message;
    engine_ = std::make_unique<Engine>(std::move(engine).value());
  }
  static void TearDownTestSuite() { engine_.reset(); }
  static inline std::unique_ptr<Engine> engine_;
};

}  // namespace scansurf::test
