// A short recording for the tests of `bimloc localize` on recorded input.
#pragma once

#include <string>

namespace bimloc::test {

// The plan the recording is of: worlds/site_office.ifc.
std::string recordingPlan();

// `bimloc simulate` of 8 s from the corridor of the plan (a walk to R101, legged odometry,
// seed 3; it converges within 2 s) into DIR/data: dataset.bag and the dataset folder. Made once
// per process and tag; returns DIR.
std::string simulatedRecording(const std::string& tag);

}  // namespace bimloc::test
