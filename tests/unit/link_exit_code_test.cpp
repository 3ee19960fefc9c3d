// The exit code of a link run that completed (tools/run/link_report.hpp): 0, or 7 (kExitForeignFrames) when
// frames of another session were refused — by this end's guard, or by the other end and reported back (the
// controller image on the target link counts its own refusals: link.target.image_refused.foreign), so that a
// refusal reaches the exit code whichever end made it.
#include <gtest/gtest.h>

#include "tools/run/link_report.hpp"

namespace gyrostab::tools {
namespace link_exit_code_test {

TEST(LinkExitCode, RefusalsOfEitherEndGiveSeven) {
  hil::LinkGuard clean;
  ::testing::internal::CaptureStderr();
  EXPECT_EQ(completed_exit_code("plant", "s", clean), 0);
  EXPECT_EQ(completed_exit_code("plant", "s", clean, 0), 0);
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");

  ::testing::internal::CaptureStderr();
  EXPECT_EQ(completed_exit_code("plant", "s", clean, 3), kExitForeignFrames);
  const std::string err = ::testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("the controller image refused 3 frames"), std::string::npos) << err;

  hil::LinkGuard refused;
  (void)refused.count(hil::GuardVerdict::kForeign);
  ::testing::internal::CaptureStderr();
  EXPECT_EQ(completed_exit_code("plant", "s", refused), kExitForeignFrames);
  EXPECT_NE(::testing::internal::GetCapturedStderr().find("1 frames on the link"), std::string::npos);
}

}  // namespace link_exit_code_test
}  // namespace gyrostab::tools
