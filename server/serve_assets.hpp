// Files `cueplan serve` carries inside the binary (cmake/embed_files.cmake writes them
// into generated sources at build time): the page's HTML, JavaScript and CSS from
// server/web/, and the shipped problems from problems/*.yaml. The server reads
// nothing from disk to answer a request.
#pragma once

#include <span>
#include <string_view>

namespace cueplan::server {

struct EmbeddedFile {
  std::string_view name;   // path relative to its directory: "index.html", "one_rail_position.yaml"
  std::string_view bytes;  // the file's contents
};

// server/web/*, in name order.
std::span<const EmbeddedFile> web_assets();
// problems/*.yaml (the one-stroke examples; not problems/routes/), in name order.
std::span<const EmbeddedFile> shipped_problem_files();

}  // namespace cueplan::server
