// Crash-proof campaigns (docs/reproducibility.md): `arcplan bench` killed with SIGKILL (the campaign
// process or one worker) and resumed gives the database of an uninterrupted run and leaves no
// temporary file; incomplete logs are found, named and run again, never given to
// ompl_benchmark_statistics; a file size limit (a full disk's write error, without root) stops the
// campaign with a clear error and keeps the completed logs; two campaigns on one --out do not run the
// same jobs at once. The suite has an iteration budget, so every run repeats exactly and the
// databases can be compared run by run.
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <functional>
#include <csignal>
#include <cstdlib>
#include <fstream>
#include <random>
#include <thread>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include "benchmarks/campaign_fixtures.h"
#include "support/command.h"

namespace arcplan::testing {
namespace {

using namespace std::chrono_literals;

// The seed of the moments at which the tests kill: a failure repeats with the same moments.
constexpr unsigned kKillMomentSeed = 20261123;

struct Reference {
  std::filesystem::path suite;
  std::filesystem::path out;
  CommandResult result;
  double wallTime = 0.0;  // s
  std::vector<std::string> runs;
};

// The uninterrupted campaign every faulty one must end up equal to: 2 problems x (RRTConnect, RRT,
// arc-auto), 3 runs of 1500 iterations, 2 worker processes.
const Reference& reference() {
  static const Reference campaign = [] {
    Reference r;
    const auto dir = freshTempDirectory("faults_reference");
    r.suite = writeTinySuite(dir, {"RRTConnect", "RRT", "arc-auto"}, 3, 1500);
    r.out = dir / "out";
    const auto start = std::chrono::steady_clock::now();
    r.result = runArcplan(benchArguments(r.suite, r.out, {"-j", "2"}));
    r.wallTime = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    r.runs = deterministicRuns(r.out / "benchmark.db");
    return r;
  }();
  return campaign;
}

std::filesystem::path logOf(const std::filesystem::path& out, const std::string& problem, const std::string& planner) {
  return out / "logs" / "tiny" / problem / (planner + ".log");
}

void waitUntil(const std::function<bool()>& condition, std::chrono::milliseconds limit) {
  const auto end = std::chrono::steady_clock::now() + limit;
  while (!condition() && std::chrono::steady_clock::now() < end) std::this_thread::sleep_for(5ms);
}

// Resumes the campaign in `out` and checks it ends as the uninterrupted one: same runs, no temporaries.
void expectResumeEqualsReference(const std::filesystem::path& out, const std::string& expectedNote = "") {
  const auto resumed = runArcplan(benchArguments(reference().suite, out, {"-j", "2"}));
  ASSERT_EQ(resumed.exitCode, 0) << resumed.err;
  if (!expectedNote.empty()) {
    EXPECT_NE(resumed.err.find(expectedNote), std::string::npos) << resumed.err;
  }
  EXPECT_EQ(deterministicRuns(out / "benchmark.db"), reference().runs);
  EXPECT_EQ(filesBelow(out / "logs", ".log").size(), 6u);
  EXPECT_TRUE(temporaryFilesBelow(out).empty()) << temporaryFilesBelow(out).front();
  EXPECT_TRUE(filesBelow(out, ".lock").empty()) << "the lock is released at the end";
}

TEST(CampaignFaults, ReferenceCampaignIsComplete) {
  const auto& r = reference();
  ASSERT_EQ(r.result.exitCode, 0) << r.result.err;
  EXPECT_EQ(r.runs.size(), 2u * 3u * 3u);
  EXPECT_TRUE(temporaryFilesBelow(r.out).empty());
}

TEST(CampaignFaults, KilledCampaignTakesItsWorkersAlongAndResumesToTheSameDatabase) {
  ASSERT_EQ(reference().result.exitCode, 0) << reference().result.err;
  const auto out = freshTempDirectory("faults_killed_parent") / "out";
  ArcplanProcess campaign(benchArguments(reference().suite, out, {"-j", "2"}));
  std::vector<pid_t> workers;
  waitUntil([&] { return (workers = campaign.children()).size() == 2 || !campaign.running(); }, 20s);
  ASSERT_EQ(workers.size(), 2u) << "the campaign should have started 2 workers: " << campaign.err();
  std::this_thread::sleep_for(300ms);  // into the first jobs
  ::kill(campaign.pid(), SIGKILL);
  ASSERT_EQ(campaign.wait(), 128 + SIGKILL) << "the campaign ended before it was killed";
  // No worker outlives the campaign (it would go on writing into the directory the resumed one owns).
  for (const pid_t worker : workers) {
    waitUntil([&] { return processGone(worker); }, 3s);
    EXPECT_TRUE(processGone(worker)) << "worker " << worker << " still runs after its campaign was killed";
  }
  ASSERT_TRUE(std::filesystem::exists(out / "campaign-1-of-1.lock"));
  // A killed writer leaves its temporary file behind; plant one of a process that is gone, as
  // SIGKILL in the middle of writing a log leaves it.
  const auto leftover = logOf(out, "pillar-000", "RRT").string() + ".tmp." + std::to_string(deadPid());
  std::filesystem::create_directories(std::filesystem::path(leftover).parent_path());
  std::ofstream(leftover) << "OMPL version 1.5.2\nExperiment tiny/pil";
  expectResumeEqualsReference(
      out, "took over the lock of a campaign that is no longer running: pid " + std::to_string(campaign.pid()));
}

TEST(CampaignFaults, CampaignKilledAtRandomMomentsResumesToTheSameDatabase) {
  ASSERT_EQ(reference().result.exitCode, 0) << reference().result.err;
  std::mt19937 random(kKillMomentSeed);
  std::uniform_real_distribution<double> moment(0.1, 0.9);
  const auto out = freshTempDirectory("faults_random_kills") / "out";
  // Two kills at seeded moments of the reference run's duration, then the resume.
  for (int kill = 0; kill < 2; ++kill) {
    const double delay = moment(random) * reference().wallTime;
    ArcplanProcess campaign(benchArguments(reference().suite, out, {"-j", "2"}));
    std::this_thread::sleep_for(std::chrono::duration<double>(delay));
    ::kill(campaign.pid(), SIGKILL);
    const int exitCode = campaign.wait();
    EXPECT_TRUE(exitCode == 128 + SIGKILL || exitCode == 0)
        << "kill " << kill << " after " << delay << " s: " << campaign.err();
  }
  expectResumeEqualsReference(out);
}

TEST(CampaignFaults, KilledWorkerIsReportedAndItsJobRunsAgainOnResume) {
  ASSERT_EQ(reference().result.exitCode, 0) << reference().result.err;
  const auto out = freshTempDirectory("faults_killed_worker") / "out";
  ArcplanProcess campaign(benchArguments(reference().suite, out, {"-j", "2"}));
  std::vector<pid_t> workers;
  waitUntil([&] { return !(workers = campaign.children()).empty() || !campaign.running(); }, 20s);
  ASSERT_FALSE(workers.empty()) << campaign.err();
  // A seeded moment early in the campaign (a fraction of the reference's duration, not a fixed time:
  // a faster build finished the whole tiny campaign before a fixed 0.1-0.6 s had passed).
  std::mt19937 random(kKillMomentSeed);
  const double delay = std::uniform_real_distribution<double>(0.1, 0.4)(random) * reference().wallTime;
  std::this_thread::sleep_for(std::chrono::duration<double>(delay));
  ::kill(workers.front(), SIGKILL);
  EXPECT_EQ(campaign.wait(), 1);
  EXPECT_NE(campaign.err().find("worker process " + std::to_string(workers.front()) + " ended abnormally (signal 9)"),
            std::string::npos)
      << campaign.err();
  EXPECT_FALSE(std::filesystem::exists(out / "benchmark.db"));
  expectResumeEqualsReference(out);
}

TEST(CampaignFaults, IncompleteLogsAreNamedRunAgainAndNeverGivenToTheStatisticsScript) {
  ASSERT_EQ(reference().result.exitCode, 0) << reference().result.err;
  const auto out = freshTempDirectory("faults_bad_logs") / "out";
  std::filesystem::copy(reference().out, out, std::filesystem::copy_options::recursive);
  std::filesystem::remove(out / "benchmark.db");
  // Cut short in the middle, as a crash of a non-atomic writer leaves it...
  const auto cut = logOf(out, "line-sphere-000", "RRT");
  std::filesystem::resize_file(cut, std::filesystem::file_size(cut) / 2);
  // ...and its last runs zeros, as a file system that never wrote the last blocks leaves it.
  const auto zeroed = logOf(out, "pillar-000", "RRTConnect");
  auto text = readFile(zeroed);
  std::fill(text.end() - 300, text.end(), '\0');
  std::ofstream(zeroed, std::ios::binary | std::ios::trunc) << text;
  // ...and one run line short of a value.
  const auto garbled = logOf(out, "pillar-000", "arc-auto");
  text = readFile(garbled);
  const auto lastRun = text.rfind("; \n");
  ASSERT_NE(lastRun, std::string::npos);
  text.erase(text.rfind("; ", lastRun - 1), 2);
  std::ofstream(garbled, std::ios::binary | std::ios::trunc) << text;

  // `bench rank` refuses to build a database from them, naming each and why.
  const auto rank = runArcplan(
      {"bench", "rank", "--logs", (out / "logs").string(), "--db", (out / "merged.db").string(), "--no-plots"});
  EXPECT_EQ(rank.exitCode, 1);
  EXPECT_NE(rank.err.find("3 incomplete or corrupt OMPL log(s), not given to ompl_benchmark_statistics"),
            std::string::npos)
      << rank.err;
  EXPECT_NE(rank.err.find(cut.string() + ": line "), std::string::npos) << rank.err;
  EXPECT_NE(rank.err.find(zeroed.string() + ": contains NUL bytes"), std::string::npos) << rank.err;
  EXPECT_NE(rank.err.find(garbled.string() + ": line "), std::string::npos) << rank.err;
  EXPECT_NE(rank.err.find("values (cut short or garbled)"), std::string::npos) << rank.err;
  EXPECT_FALSE(std::filesystem::exists(out / "merged.db"));

  // The campaign reports them, runs their jobs again and builds the reference database.
  const auto resumed = runArcplan(benchArguments(reference().suite, out, {"-j", "2"}));
  ASSERT_EQ(resumed.exitCode, 0) << resumed.err;
  for (const auto& log : {cut, zeroed, garbled}) {
    EXPECT_NE(resumed.err.find("bench: note: " + log.string() + " is incomplete ("), std::string::npos) << resumed.err;
  }
  EXPECT_NE(resumed.err.find("bench: 3 job(s) run, 3 already done"), std::string::npos) << resumed.err;
  EXPECT_EQ(deterministicRuns(out / "benchmark.db"), reference().runs);
}

TEST(CampaignFaults, FileSizeLimitStopsTheCampaignWithAClearErrorAndKeepsCompletedLogs) {
  ASSERT_EQ(reference().result.exitCode, 0) << reference().result.err;
  std::uintmax_t smallestLog = UINTMAX_MAX;
  for (const auto& log : filesBelow(reference().out / "logs", ".log")) {
    smallestLog = std::min(smallestLog, std::filesystem::file_size(log));
  }
  // Below every log, above the settings and scene files written first: the first log cannot be written.
  const long limit = static_cast<long>(smallestLog / 2);
  ASSERT_GT(limit, static_cast<long>(std::filesystem::file_size(reference().out / "campaign.json")));
  const auto out = freshTempDirectory("faults_file_size") / "out";
  ArcplanProcess limited(benchArguments(reference().suite, out, {"-j", "1"}), limit);
  EXPECT_EQ(limited.wait(), 1);
  const auto err = limited.err();
  EXPECT_NE(err.find("arcplan: error: the campaign stopped: writing " + out.string()), std::string::npos) << err;
  EXPECT_NE(err.find("failed: File too large"), std::string::npos) << err;
  EXPECT_NE(err.find("make room (or raise the file size limit) and run the same command again to resume"),
            std::string::npos)
      << err;
  // It stopped at the first failed write instead of running every job to fail the same way.
  EXPECT_EQ(err.find("job(s) failed"), std::string::npos) << err;
  EXPECT_TRUE(filesBelow(out / "logs", ".log").empty());
  EXPECT_TRUE(temporaryFilesBelow(out).empty()) << temporaryFilesBelow(out).front();
  EXPECT_FALSE(std::filesystem::exists(out / "benchmark.db"));
  expectResumeEqualsReference(out);
}

// tmpfs allocates whole pages per file.
std::uintmax_t pagesOf(std::uintmax_t bytes) { return (bytes + 4095) / 4096; }

// A real full disk: --out on a tmpfs with room for the settings, the scenes and about half of the logs.
// Mounting needs root (CI runs as root); as another user the test fails saying so, it is not skipped.
TEST(CampaignFaults, FullDiskStopsTheCampaignWithAClearErrorAndKeepsOnlyCompleteLogs) {
  ASSERT_EQ(::geteuid(), 0u) << "this test mounts a small tmpfs as --out and needs root (CI runs as root); "
                                "run scripts/test as root";
  ASSERT_EQ(reference().result.exitCode, 0) << reference().result.err;
  std::uintmax_t pagesBeforeLogs = 2;  // the lock, slack
  for (const auto& file : filesBelow(reference().out)) {
    const auto name = file.lexically_relative(reference().out).string();
    const bool writtenAfterTheLogs = name.rfind("logs/", 0) == 0 || name.rfind("benchmark.db", 0) == 0 ||
                                     name.rfind("ranking.", 0) == 0 || name.rfind("plots/", 0) == 0;
    if (!writtenAfterTheLogs) pagesBeforeLogs += pagesOf(std::filesystem::file_size(file));
  }
  std::uintmax_t logPages = 0;
  for (const auto& log : filesBelow(reference().out / "logs", ".log"))
    logPages += pagesOf(std::filesystem::file_size(log));
  ASSERT_GE(logPages, 6u);
  const auto disk = freshTempDirectory("faults_full_disk") / "disk";
  std::filesystem::create_directories(disk);
  const std::string size = std::to_string((pagesBeforeLogs + logPages / 2) * 4) + "k";
  ASSERT_EQ(std::system(("mount -t tmpfs -o size=" + size + " arcplan-full-disk " + disk.string()).c_str()), 0);
  struct Unmount {
    std::filesystem::path point;
    ~Unmount() { (void)std::system(("umount " + point.string()).c_str()); }
  } unmount{disk};

  const auto out = disk / "out";
  const auto full = runArcplan(benchArguments(reference().suite, out, {"-j", "1"}));
  EXPECT_EQ(full.exitCode, 1) << full.err;
  EXPECT_NE(full.err.find("arcplan: error: the campaign stopped: writing " + out.string()), std::string::npos)
      << full.err;
  EXPECT_NE(full.err.find("No space left on device"), std::string::npos) << full.err;
  const auto kept = filesBelow(out / "logs", ".log");
  EXPECT_LT(kept.size(), 6u);
  EXPECT_TRUE(temporaryFilesBelow(out).empty()) << temporaryFilesBelow(out).front();
  EXPECT_FALSE(std::filesystem::exists(out / "benchmark.db"));

  // Given room, the same command resumes: every kept log is complete (none is reported and re-run).
  const auto roomy = freshTempDirectory("faults_full_disk_resumed") / "out";
  std::filesystem::copy(out, roomy, std::filesystem::copy_options::recursive);
  const auto resumed = runArcplan(benchArguments(reference().suite, roomy, {"-j", "2"}));
  ASSERT_EQ(resumed.exitCode, 0) << resumed.err;
  EXPECT_EQ(resumed.err.find("is incomplete"), std::string::npos) << resumed.err;
  EXPECT_EQ(deterministicRuns(roomy / "benchmark.db"), reference().runs);
}

TEST(CampaignFaults, DatabaseThatCannotBeWrittenLeavesCompleteLogsAndNoHalfDatabase) {
  ASSERT_EQ(reference().result.exitCode, 0) << reference().result.err;
  std::uintmax_t largestLog = 0;
  for (const auto& log : filesBelow(reference().out / "logs", ".log")) {
    largestLog = std::max(largestLog, std::filesystem::file_size(log));
  }
  // Room for every log (their sizes vary by a few digits of timing), not for the database.
  const long limit = static_cast<long>(largestLog * 3 / 2);
  ASSERT_LT(limit, static_cast<long>(std::filesystem::file_size(reference().out / "benchmark.db")));
  const auto out = freshTempDirectory("faults_database_size") / "out";
  ArcplanProcess limited(benchArguments(reference().suite, out, {"-j", "2"}), limit);
  EXPECT_EQ(limited.wait(), 1);
  const auto err = limited.err();
  EXPECT_NE(err.find("ompl_benchmark_statistics failed"), std::string::npos) << err;
  EXPECT_NE(err.find("every job's log is complete and kept in " + (out / "logs").string()), std::string::npos) << err;
  EXPECT_EQ(filesBelow(out / "logs", ".log").size(), 6u);
  EXPECT_FALSE(std::filesystem::exists(out / "benchmark.db"));
  EXPECT_TRUE(temporaryFilesBelow(out).empty()) << temporaryFilesBelow(out).front();
  expectResumeEqualsReference(out);
}

TEST(CampaignFaults, SecondCampaignOnTheSameOutputSaysWhoHoldsItAndExitsNonZero) {
  ASSERT_EQ(reference().result.exitCode, 0) << reference().result.err;
  const auto out = freshTempDirectory("faults_two_campaigns") / "out";
  ArcplanProcess first(benchArguments(reference().suite, out, {"-j", "1"}));
  const auto lock = out / "campaign-1-of-1.lock";
  waitUntil([&] { return std::filesystem::exists(lock) || !first.running(); }, 20s);
  ASSERT_TRUE(std::filesystem::exists(lock)) << first.err();
  const auto holder = nlohmann::json::parse(readFile(lock));
  char host[256] = {};
  ::gethostname(host, sizeof host - 1);
  EXPECT_EQ(holder.at("pid").get<int>(), first.pid());
  EXPECT_EQ(holder.at("host").get<std::string>(), host);
  EXPECT_EQ(holder.at("shard").get<std::string>(), "1/1");

  const std::string held = "is in use by another campaign: pid " + std::to_string(first.pid()) + " on host " + host;
  const auto second = runArcplan(benchArguments(reference().suite, out, {"-j", "1"}));
  EXPECT_EQ(second.exitCode, 1);
  EXPECT_NE(second.err.find(held), std::string::npos) << second.err;
  // A shard shares jobs with the whole campaign: refused too.
  const auto shard = runArcplan(benchArguments(reference().suite, out, {"-j", "1", "--shard", "2/2"}));
  EXPECT_EQ(shard.exitCode, 1);
  EXPECT_NE(shard.err.find(held), std::string::npos) << shard.err;
  ASSERT_TRUE(first.running()) << "the first campaign ended before the others were refused; too fast to test";
  EXPECT_EQ(first.wait(), 0) << first.err();
  EXPECT_FALSE(std::filesystem::exists(lock));
  EXPECT_EQ(deterministicRuns(out / "benchmark.db"), reference().runs);
}

TEST(CampaignFaults, ShardsWithoutCommonJobsShareOneOutputAtOnce) {
  ASSERT_EQ(reference().result.exitCode, 0) << reference().result.err;
  const auto out = freshTempDirectory("faults_two_shards") / "out";
  ArcplanProcess first(benchArguments(reference().suite, out, {"-j", "1", "--shard", "1/2"}));
  ArcplanProcess second(benchArguments(reference().suite, out, {"-j", "1", "--shard", "2/2"}));
  EXPECT_EQ(first.wait(), 0) << first.err();
  EXPECT_EQ(second.wait(), 0) << second.err();
  // Whichever finished last built the database of all 6 jobs.
  expectResumeEqualsReference(out);
}

TEST(CampaignFaults, StaleLockOfAGoneProcessIsTakenOverAndAnotherHostsLockIsNot) {
  ASSERT_EQ(reference().result.exitCode, 0) << reference().result.err;
  const auto out = freshTempDirectory("faults_stale_lock") / "out";
  std::filesystem::copy(reference().out, out, std::filesystem::copy_options::recursive);
  char host[256] = {};
  ::gethostname(host, sizeof host - 1);
  const pid_t gone = deadPid();
  std::ofstream(out / "campaign-1-of-2.lock") << nlohmann::json{
      {"pid", gone},
      {"host", host},
      {"shard", "1/2"},
      {"started_utc", "2026-01-01T00:00:00Z"}}.dump();
  expectResumeEqualsReference(out, "took over the lock of a campaign that is no longer running: pid " +
                                       std::to_string(gone) + " on host " + host + " (shard 1/2");

  // A lock from another host cannot be checked from here: refused, with what to do if it is stale.
  const auto elsewhere = out / "campaign-1-of-1.lock";
  std::ofstream(elsewhere) << nlohmann::json{
      {"pid", 1},
      {"host", "build-node-7.invalid"},
      {"shard", "1/1"},
      {"started_utc",
       "2026-01-01T00:00:00Z"}}.dump();
  const auto refused = runArcplan(benchArguments(reference().suite, out));
  EXPECT_EQ(refused.exitCode, 1);
  EXPECT_NE(refused.err.find("pid 1 on host build-node-7.invalid (shard 1/1, started 2026-01-01T00:00:00Z, lock file " +
                             elsewhere.string() + ")"),
            std::string::npos)
      << refused.err;
  EXPECT_NE(refused.err.find("if that process is gone from host build-node-7.invalid, delete the lock file"),
            std::string::npos)
      << refused.err;
  EXPECT_TRUE(std::filesystem::exists(elsewhere));
}

}  // namespace
}  // namespace arcplan::testing
