#include "arcplan/report/model_series.h"

#include <fstream>
#include <optional>

#include "arcplan/common/error.h"
#include "arcplan/common/text_parsing.h"

namespace arcplan::report {
namespace {

const std::vector<std::string> kRequired{"channel", "time", "measured", "predicted"};
const std::vector<std::string> kSignals{"q", "qd", "qdd", "tau", "temperature"};

struct RawChannel {
  ChannelSeries series;
  std::map<std::string, std::vector<std::optional<double>>> signals;
};

std::vector<double> strided(const std::vector<double>& values, std::size_t stride) {
  std::vector<double> out;
  for (std::size_t i = 0; i < values.size(); i += stride) out.push_back(values[i]);
  return out;
}

}  // namespace

std::vector<ChannelSeries> readModelSeries(const std::filesystem::path& file, std::size_t maxSamples) {
  std::ifstream in(file);
  if (!in) throw Error(file.string() + ": cannot open model series file");
  std::string line;
  if (!std::getline(in, line))
    throw Error(file.string() + ":1: empty file, expected a header (channel,index,time,...)");
  std::map<std::string, std::size_t> column;
  const auto header = splitFields(trim(line), ',');
  for (std::size_t i = 0; i < header.size(); ++i) column[std::string(trim(header[i]))] = i;
  for (const auto& name : kRequired) {
    if (column.count(name) == 0) throw Error(file.string() + ":1: header has no column '" + name + "'");
  }
  std::vector<RawChannel> channels;
  std::map<std::string, std::size_t> channelIndex;
  for (int number = 2; std::getline(in, line); ++number) {
    if (trim(line).empty()) continue;
    const auto fields = splitFields(line, ',');
    const auto where = file.string() + ":" + std::to_string(number) + ": ";
    if (fields.size() != header.size()) {
      throw Error(where + std::to_string(fields.size()) + " fields, expected " + std::to_string(header.size()));
    }
    const auto value = [&](const std::string& name) -> std::optional<double> {
      const auto text = trim(fields[column.at(name)]);
      if (text.empty()) return std::nullopt;
      const auto parsed = parseDouble(text);
      if (!parsed) throw Error(where + "column " + name + ": '" + std::string(text) + "' is not a number");
      return parsed;
    };
    const std::string name(trim(fields[column.at("channel")]));
    auto [found, added] = channelIndex.emplace(name, channels.size());
    if (added) channels.push_back({ChannelSeries{name, {}, {}, {}, {}}, {}});
    auto& channel = channels[found->second];
    for (const auto& required : {"time", "measured", "predicted"}) {
      if (!value(required)) throw Error(where + "column " + std::string(required) + " is empty");
    }
    channel.series.time.push_back(*value("time"));
    channel.series.measured.push_back(*value("measured"));
    channel.series.predicted.push_back(*value("predicted"));
    for (const auto& signal : kSignals) {
      if (column.count(signal) != 0) channel.signals[signal].push_back(value(signal));
    }
  }
  if (channels.empty()) throw Error(file.string() + ": no samples after the header");
  std::vector<ChannelSeries> result;
  for (auto& raw : channels) {
    const std::size_t n = raw.series.time.size();
    const std::size_t stride = maxSamples > 0 && n > maxSamples ? (n + maxSamples - 1) / maxSamples : 1;
    ChannelSeries series{raw.series.channel,
                         strided(raw.series.time, stride),
                         strided(raw.series.measured, stride),
                         strided(raw.series.predicted, stride),
                         {}};
    for (const auto& [signal, values] : raw.signals) {
      std::vector<double> complete;
      for (const auto& v : values) {
        if (!v) break;
        complete.push_back(*v);
      }
      if (complete.size() == values.size()) series.signals[signal] = strided(complete, stride);
    }
    result.push_back(std::move(series));
  }
  return result;
}

}  // namespace arcplan::report
