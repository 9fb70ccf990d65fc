#pragma once
// The measured-vs-predicted series a model session keeps (<prefix>_series.csv, written by
// model/plots.h): header "channel,index,time,measured,predicted,base,q,qd,qdd,tau,temperature",
// one row per sample and channel, empty fields for signals the log does not have.
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace arcplan::report {

struct ChannelSeries {
  std::string channel;  // "actual_current_1", "gearbox/direct"
  std::vector<double> time, measured, predicted;
  std::map<std::string, std::vector<double>> signals;  // only the signals present on every row
};

// Channels in file order, at most `maxSamples` evenly strided samples each (0: all). Throws
// arcplan::Error naming the file and line for a missing column or a malformed number.
std::vector<ChannelSeries> readModelSeries(const std::filesystem::path& file, std::size_t maxSamples = 0);

}  // namespace arcplan::report
