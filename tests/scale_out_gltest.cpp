// docs/scale-out.md's thumbnail farms, run as written: the command lines of its Kubernetes
// Indexed Job and Slurm job array, once for every index, over one list of scenes.
#include <gtest/gtest.h>

#include <map>
#include <nlohmann/json.hpp>
#include <regex>

#include "tests/cli_support.h"

namespace manylight::testing {
namespace {

// One scheduler's example: the arguments of its command line, from shard_task.sh on, the
// task count it gives, and how it tells a task which one it is.
struct FarmExample {
  std::vector<std::string> command;
  int tasks = 0;
  bool kubernetes = false;
  std::string shardCount;  // Kubernetes: the SHARD_COUNT the manifest sets
  // The variables the scheduler sets in task `index`.
  std::string environment(int index) const {
    return kubernetes
               ? "JOB_COMPLETION_INDEX=" + std::to_string(index) + " SHARD_COUNT=" + shardCount
               : "SLURM_ARRAY_TASK_ID=" + std::to_string(index) +
                     " SLURM_ARRAY_TASK_MIN=0 SLURM_ARRAY_TASK_COUNT=" + std::to_string(tasks);
  }
};

// The fenced code block of docs/scale-out.md that begins with "```" + language.
std::string codeBlock(const std::string& doc, const std::string& language) {
  const std::size_t open = doc.find("```" + language + "\n");
  EXPECT_NE(open, std::string::npos) << "no ```" << language << " block";
  if (open == std::string::npos) return {};
  const std::size_t start = open + 4 + language.size();
  return doc.substr(start, doc.find("```", start) - start);
}

std::string firstMatch(const std::string& text, const std::string& pattern) {
  std::smatch m;
  EXPECT_TRUE(std::regex_search(text, m, std::regex(pattern))) << pattern << " in:\n" << text;
  return m.size() > 1 ? m[1].str() : std::string();
}

FarmExample kubernetesExample(const std::string& doc) {
  const std::string yaml = codeBlock(doc, "yaml");
  FarmExample e;
  e.kubernetes = true;
  e.tasks = std::stoi(firstMatch(yaml, "\\n  completions: (\\d+)\\n"));
  e.shardCount = firstMatch(yaml, "name: SHARD_COUNT\\n\\s*value: \"(\\d+)\"");
  e.command = nlohmann::json::parse(firstMatch(yaml, "command: (\\[.*\\])"))
                  .get<std::vector<std::string>>();
  return e;
}

FarmExample slurmExample(const std::string& doc) {
  const std::string script = codeBlock(doc, "sh");
  FarmExample e;
  EXPECT_EQ(firstMatch(script, "#SBATCH --array=(\\d+)-"), "0");
  e.tasks = std::stoi(firstMatch(script, "#SBATCH --array=0-(\\d+)")) + 1;
  std::istringstream srun(firstMatch(script, "\\nsrun ([^\\n]*)"));
  bool scriptSeen = false;
  for (std::string word; srun >> word;) {
    scriptSeen = scriptSeen || word.find("shard_task.sh") != std::string::npos;
    if (scriptSeen) e.command.push_back(word);
  }
  return e;
}

// Runs every task of `example` with /opt/manylight/ standing for the repository and /data/
// for `data`; checks that each exits 0 and that their shards hold each of `scenes` once.
void runFarm(const FarmExample& example, const fs::path& data,
             const std::vector<std::string>& scenes) {
  ASSERT_GE(example.command.size(), 3u);
  std::string list;
  for (const std::string& s : scenes) list += s + "\n";
  fs::create_directories(data);
  std::ofstream(data / "scenes.txt") << "# the farm's scenes\n" << list;
  std::string args;
  for (std::string word : example.command) {
    for (const auto& [from, to] :
         {std::pair<std::string, std::string>{"/opt/manylight/", MANYLIGHT_SOURCE_DIR "/"},
          {"/data/", data.string() + "/"}}) {
      if (word.rfind(from, 0) == 0) word = to + word.substr(from.size());
    }
    args += " '" + word + "'";
  }
  std::map<std::string, int> rendered;  // scene → how many shards rendered it
  for (int i = 0; i < example.tasks; ++i) {
    const std::string command = example.environment(i) + " MANYLIGHT=" MANYLIGHT_BIN + args +
                                " 2>" + (data / "stderr.txt").string();
    const int status = std::system(command.c_str());
    ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << command << "\n"
                                                               << readFile(data / "stderr.txt");
    const fs::path statsFile =
        data / "thumbs" /
        ("shard-" + std::to_string(i) + "-of-" + std::to_string(example.tasks) + ".json");
    const auto stats = nlohmann::json::parse(readFile(statsFile));
    EXPECT_EQ(stats["failed"], 0);
    for (const auto& s : stats["scenes"]) {
      ++rendered[s["scene"].get<std::string>()];
      EXPECT_TRUE(fs::exists(s["output"].get<std::string>())) << s["output"];
    }
  }
  for (const std::string& s : scenes) EXPECT_EQ(rendered[s], 1) << s;
  EXPECT_EQ(rendered.size(), scenes.size()) << "a shard rendered a scene not in the list";
  int thumbnails = 0;
  for (const auto& f : fs::directory_iterator(data / "thumbs"))
    thumbnails += f.path().extension() == ".png";
  EXPECT_EQ(thumbnails, int(scenes.size()));
}

TEST(ScaleOut, ExamplesRenderEverySceneOnce) {
  const std::string doc = readFile(MANYLIGHT_SOURCE_DIR "/docs/scale-out.md");
  std::vector<std::string> scenes;
  for (int i = 0; i < 10; ++i) {
    RoomOptions o;
    o.lightCount = 2;
    o.seed = std::uint32_t(i + 1);
    o.textured = false;
    scenes.push_back(roomScene(o, "room" + std::to_string(i) + ".gltf"));
  }
  const FarmExample job = kubernetesExample(doc);
  EXPECT_EQ(job.shardCount, std::to_string(job.tasks)) << "SHARD_COUNT must be completions";
  ASSERT_LT(job.tasks, 10) << "some shards should get two scenes";
  {
    SCOPED_TRACE("Kubernetes Indexed Job");
    runFarm(job, testFolder() / "k8s", scenes);
  }
  const FarmExample array = slurmExample(doc);
  EXPECT_EQ(array.command, job.command) << "both run the same task";
  ASSERT_GT(array.tasks, 6) << "some shards should get none";
  {
    SCOPED_TRACE("Slurm job array");
    runFarm(array, testFolder() / "slurm", {scenes.begin(), scenes.begin() + 6});
  }
}

}  // namespace
}  // namespace manylight::testing
