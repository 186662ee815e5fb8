// One validating Gpu shared by the GPU tests (creating a device per test is slow on lavapipe);
// every test fails if the validation layer said anything while it ran.
#pragma once
#include <gtest/gtest.h>

#include <memory>

#include "renderer/vk/gpu.h"

namespace gib::test {

Gpu& shared_gpu();

class GpuTest : public ::testing::Test {
 protected:
  void SetUp() override { shared_gpu().clear_validation_messages(); }
  void TearDown() override {
    for (auto& m : shared_gpu().validation_messages()) ADD_FAILURE() << "validation: " << m;
  }
  Gpu& gpu() { return shared_gpu(); }
};

}  // namespace gib::test
