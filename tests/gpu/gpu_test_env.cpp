#include "gpu/gpu_test_env.h"

#include <cstdio>
#include <memory>

namespace scansurf::test {
namespace {

std::mutex gMessagesMutex;
std::vector<std::string> gMessages;
std::unique_ptr<gpu::Context> gContext;

}  // namespace

void recordValidationMessage(std::string_view message) {
  std::lock_guard lock(gMessagesMutex);
  gMessages.emplace_back(message);
}

EngineOptions validatedEngineOptions() {
  EngineOptions options;
  options.validation = true;
  options.onValidationMessage = recordValidationMessage;
  return options;
}

gpu::Context& sharedContext() {
  if (!gContext) {
    auto ctx = gpu::Context::create(validatedEngineOptions());
    if (!ctx) {
      std::fprintf(stderr, "cannot create a Vulkan context: %s\n", ctx.error().message.c_str());
      std::abort();
    }
    gContext = std::move(ctx).value();
  }
  return *gContext;
}

void GpuTest::SetUp() {
  std::lock_guard lock(gMessagesMutex);
  gMessages.clear();
}

void GpuTest::TearDown() {
  std::lock_guard lock(gMessagesMutex);
  for (const std::string& m : gMessages) ADD_FAILURE() << m;
  gMessages.clear();
}

}  // namespace scansurf::test

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  const int result = RUN_ALL_TESTS();
  scansurf::test::gContext.reset();
  return result;
}
