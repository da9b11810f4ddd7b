// Quiet by default (issue 13, part 5): PCL's console messages stay off unless bimloc is asked
// for them (`bimloc --verbose`, bimloc::setVerbose). The truth is PCL's own level.
#include <bimloc/planes/plane_extraction.hpp>
#include <bimloc/verbosity.hpp>

#include <gtest/gtest.h>
#include <pcl/console/print.h>

TEST(Quiet, PclSaysNothingUnlessVerbose) {
  // A box of points: the extraction runs PCL's voxel grid and RANSAC.
  std::vector<Eigen::Vector3f> points;
  for (int i = 0; i < 40; ++i)
    for (int j = 0; j < 20; ++j) {
      points.emplace_back(0.1f * i - 2.0f, 3.0f, 0.1f * j);
      points.emplace_back(-2.0f, 0.1f * i - 2.0f, 0.1f * j);
    }
  pcl::console::setVerbosityLevel(pcl::console::L_INFO);  // PCL's default
  ASSERT_FALSE(bimloc::verbose());
  (void)bimloc::planes::extractPlanes(points);
  EXPECT_EQ(pcl::console::getVerbosityLevel(), pcl::console::L_ALWAYS);
  bimloc::setVerbose(true);
  (void)bimloc::planes::extractPlanes(points);
  EXPECT_EQ(pcl::console::getVerbosityLevel(), pcl::console::L_INFO);
  bimloc::setVerbose(false);
}
