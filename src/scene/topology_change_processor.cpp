#include "topology_change_processor.h"

#include "fastcorot/core/error.h"

#include <cmath>
#include <fstream>
#include <sstream>

namespace fastcorot::scene_detail {

namespace {

// The words of a file with the line each is on.
struct Word {
  std::string text;
  int line;
};

class WordReader {
 public:
  WordReader(const std::filesystem::path& path) : file_(path.string()) {
    std::ifstream in(path);
    if (!in) throw make_error(file_, ": cannot open the topological change file");
    std::string line;
    for (int number = 1; std::getline(in, line); ++number) {
      std::istringstream words(line);
      for (std::string word; words >> word;) words_.push_back({word, number});
    }
  }

  bool done() const { return next_ == words_.size(); }
  const Word& peek() const { return words_[next_]; }
  Word take(const char* what) {
    if (done()) throw make_error(file_, ": ends where ", what, " was expected");
    return words_[next_++];
  }
  double number(const char* what) {
    const Word word = take(what);
    std::size_t used = 0;
    double value = 0;
    try {
      value = std::stod(word.text, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != word.text.size() || !std::isfinite(value)) {
      throw make_error(file_, ":", word.line, ": \"", word.text, "\" is not ", what);
    }
    return value;
  }
  Index index(const char* what) {
    const int line = done() ? 0 : peek().line;
    const double value = number(what);
    if (!(value >= 0) || value != std::floor(value) || value > 2e9) {
      throw make_error(file_, ":", line, ": ", value, " is not ", what);
    }
    return static_cast<Index>(value);
  }
  const std::string& file() const { return file_; }

 private:
  std::string file_;
  std::vector<Word> words_;
  std::size_t next_ = 0;
};

}  // namespace

std::vector<TopologyEvent> read_topology_changes(const std::filesystem::path& path) {
  WordReader in(path);
  std::vector<TopologyEvent> events;
  while (!in.done()) {
    const Word word = in.take("T=");
    const std::string where = in.file() + ":" + std::to_string(word.line);
    if (word.text == "T=") {
      TopologyEvent event;
      event.time = in.number("a time after T=");
      event.where = where;
      if (!events.empty() && event.time < events.back().time) {
        throw make_error(where, ": T= ", event.time, " comes after T= ", events.back().time,
                         " (times must not decrease)");
      }
      events.push_back(std::move(event));
      continue;
    }
    if (events.empty()) throw make_error(where, ": \"", word.text, "\" before the first T=");
    TopologyEvent& event = events.back();
    if (word.text == "REMOVE=") {
      const Index count = in.index("a count after REMOVE=");
      for (Index i = 0; i < count; ++i) event.remove.push_back(in.index("a tetrahedron index"));
    } else if (word.text == "ADD=") {
      const Word kind = in.take("an element kind after ADD=");
      if (kind.text != "Tetrahedra" && kind.text != "Tetrahedron") {
        throw make_error(in.file(), ":", kind.line, ": ADD= ", kind.text,
                         ": only tetrahedra can be added to a tetrahedral topology");
      }
      const Index count = in.index("a count after ADD= Tetrahedra");
      for (Index i = 0; i < count; ++i) {
        Tetrahedron tet{};
        for (Index& v : tet) v = in.index("a point index");
        event.add.push_back(tet);
      }
    } else {
      throw make_error(where, ": \"", word.text,
                       "\" is not a change this reader knows (T=, REMOVE=, ADD= Tetrahedra)");
    }
  }
  return events;
}

TopologyScript build_topology_script(SceneData& data, Component& c, std::shared_ptr<TetMesh> mesh) {
  TopologyScript script;
  script.where = c.where();
  script.mesh = std::move(mesh);
  for (const char* other : {"pointsToRemove", "edgesToRemove", "trianglesToRemove", "quadsToRemove", "hexahedraToRemove"}) {
    if (!data.indices(c, other).empty()) {
      throw make_error(c.where(), ": ", other, ": only tetrahedra can be removed from a tetrahedral topology");
    }
  }
  if (data.boolean(c, "saveIndicesAtInit", false)) {
    throw make_error(c.where(), ": saveIndicesAtInit (incision paths on triangles) is not supported");
  }
  if (data.boolean(c, "loop", false)) throw make_error(c.where(), ": loop is not supported");
  const double interval = data.real(c, "interval", 0);
  if (!(interval >= 0) || !std::isfinite(interval)) {
    throw make_error(c.where(), ": interval = ", interval, ": must be a finite value >= 0");
  }
  if (data.boolean(c, "useDataInputs", false)) {
    TopologyEvent event;
    event.time = data.real(c, "timeToRemove", 0);
    event.remove = data.indices(c, "tetrahedraToRemove");
    event.where = "tetrahedraToRemove";
    if (!std::isfinite(event.time)) throw make_error(c.where(), ": timeToRemove must be finite");
    script.strictly_after = true;
    script.interval = interval;
    if (!event.remove.empty()) script.events.push_back(std::move(event));
    return script;
  }
  const std::string name = data.text(c, "filename", "");
  if (name.empty()) {
    throw make_error(c.where(), ": give a filename of timed changes, or useDataInputs=\"true\" with "
                                "timeToRemove and tetrahedraToRemove");
  }
  const double shift = data.real(c, "shift", 0);
  if (!std::isfinite(shift)) throw make_error(c.where(), ": shift must be finite");
  try {
    script.events = read_topology_changes(c.object->location.file.parent_path() / name);
  } catch (const Error& error) {
    throw error_at(c.where(), error);
  }
  script.shift = shift;  // SOFA compares T with the time plus shift
  return script;
}

}  // namespace fastcorot::scene_detail
