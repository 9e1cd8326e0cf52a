#include "serve_problems.hpp"

#include <utility>

#include "serve_assets.hpp"

namespace cueplan::server {
using namespace cueplan::api;  // the api's types and checks, as the server's own

namespace prob = cueplan::problems;
using nlohmann::ordered_json;

std::vector<Example> shipped_examples(std::string* error) {
  std::vector<Example> examples;
  for (const EmbeddedFile& file : shipped_problem_files()) {
    const std::string name(file.name);
    std::string why;
    std::optional<ordered_json> fields = problem_yaml_to_json(file.bytes, &why);
    prob::LoadResult loaded = prob::parse_problem(std::string(file.bytes), "problems/" + name);
    if (!fields || !loaded.ok()) {
      *error = "shipped problem " + name + " does not load: " + (fields ? loaded.error : why);
      return {};
    }
    Example e;
    e.name = loaded.problem->name;
    e.file = name;
    // The name first, as the files write it; a file without one gets its file's stem.
    e.problem = ordered_json::object();
    e.problem["name"] = e.name;
    for (const auto& [key, value] : fields->items()) e.problem[key] = value;
    e.loaded = std::move(*loaded.problem);
    examples.push_back(std::move(e));
  }
  return examples;
}

}  // namespace cueplan::server
