// GPU test fixture: one validated Vulkan context for the whole run (lavapipe in CI); any
// validation message during a test fails that test.
#pragma once

#include <gtest/gtest.h>

#include <mutex>
#include <string>
#include <vector>

#include "gpu/context.h"
#include "scansurf/engine.h"

namespace scansurf::test {

// Options that route validation messages into the fixture's log.
EngineOptions validatedEngineOptions();
gpu::Context& sharedContext();

class GpuTest : public ::testing::Test {
 protected:
  void SetUp() override;
  void TearDown() override;
};

}  // namespace scansurf::test
