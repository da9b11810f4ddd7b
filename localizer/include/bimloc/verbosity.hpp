// The libraries under the localizer are quiet unless asked (issue 13, part 5): PCL prints its
// console messages ("[pcl::...] ...") into the results a user reads, for events that are
// ordinary for RANSAC (a degenerate sample, no model in a small pool).
#pragma once

namespace bimloc {

// false (the default): PCL prints nothing; true: PCL's own default level (errors, warnings, info).
void setVerbose(bool verbose);
bool verbose();

}  // namespace bimloc
