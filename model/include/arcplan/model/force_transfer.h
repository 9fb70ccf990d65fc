#pragma once
// Quasi-static gearbox force-transfer measurements (seed thesis chapter 2, tables 2.2–2.4):
// equilibrium points of input torque against output torque, DIRECT (the input drives the load,
// motoring) and INDIRECT (the load drives the input, regenerating), for several Harmonic Drives.
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

namespace arcplan::model {

struct ForceTransferPoint {
  std::string gearbox;
  double ratio = 0.0;         // ideal velocity ratio i (output torque / input torque without friction)
  int series = 1;             // repeat of the measurement
  bool direct = true;         // DIRECT (motoring) or INDIRECT (regenerating)
  double outputTorque = 0.0;  // N·m
  double inputTorque = 0.0;   // N·m
  std::size_t line = 0;       // 1-based line in the file
};

// Reads the CSV of shared/data/thesis/force_transfer_diagrams.csv (columns gearbox, ratio,
// series, direction, tau_out_Nm, tau_in_Nm; others ignored). Throws arcplan::Error naming the
// file, line and column when a column is missing or a value is not what it should be.
std::vector<ForceTransferPoint> readForceTransferData(const std::filesystem::path& file);

}  // namespace arcplan::model
