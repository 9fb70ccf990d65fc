#pragma once
// Every name of every trajectory metric, one row per metric (docs/metrics.md explains them). The
// JSON of `plan` and `scale`, the benchmark run properties, the ranking (md, json, csv) and the box
// plots all iterate this table, so a metric is named in exactly one place.
#include <string>
#include <vector>

#include "arcplan/trajectory/metrics.h"

namespace arcplan::trajectory {

struct MetricDescriptor {
  // Where the value lives in TrajectoryMetrics; nullptr for the solve time, which is not a property
  // of the trajectory (the planner measures it and writes its own run property).
  double TrajectoryMetrics::*member;
  std::string key;   // JSON key and ranking key, unit last: "tcp_path_length_m"
  std::string unit;  // SI unit, "1" for ratios
  // Benchmark run property arcplan writes ("tcp path length REAL"): only [A-Za-z0-9 ] and the SQL
  // type, because ompl_benchmark_statistics pastes it unquoted into SQL; empty when OMPL writes
  // the value itself (the joint path length is OMPL's "solution length").
  std::string omplProperty;
  std::vector<std::string> columns;  // its columns in the benchmark database; the first non-NULL wins
  std::string label;                 // for tables and plots: "TCP path length (m)"
  // Which way is an improvement: `bench compare` calls a change better or worse by this (a shorter
  // path, time or time above the limit is better; a larger clearance or mean TCP speed is better).
  bool lowerIsBetter;
};

// In the order of the ranking's tables and of ranking.csv: execution time, TCP path length, joint
// path length, solve time, mean and peak TCP speed, time above the limit, clearance, joint speeds.
const std::vector<MetricDescriptor>& metricDescriptors();

// The row with this key; throws arcplan::Error for an unknown key.
const MetricDescriptor& metricDescriptor(const std::string& key);
// The row of a member of TrajectoryMetrics, so that code outside this table names a metric by its
// member rather than by a copy of its key.
const MetricDescriptor& metricDescriptor(double TrajectoryMetrics::*member);
// The row of the planner's solve time, the one metric that is not a member of TrajectoryMetrics.
const MetricDescriptor& solveTimeDescriptor();

}  // namespace arcplan::trajectory
