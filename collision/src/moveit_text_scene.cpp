// The `.scene` text files of MoveIt (RViz's Motion Planning panel, "Export"): a name line, then per
// object "* id", [object position and quaternion lines, newer layout], the shape count, and per shape
// its type, dimensions, position, quaternion [x y z w] and colour; [subframes, newer layout]; "." ends
// the file. The newer layout is recognised as MoveIt does: the line after the first "* id" holds
// several numbers (a position) instead of one (the shape count). Poses are in the planning frame.
#include <fstream>
#include <sstream>

#include "arcplan/collision/moveit_scene.h"
#include "arcplan/common/error.h"
#include "arcplan/common/text_parsing.h"
#include "moveit_reading.h"
#include "moveit_scene_building.h"

namespace arcplan::collision {
namespace {

// Bounds that keep a corrupt count from allocating without end.
constexpr long long kMaximumShapes = 100000;
constexpr long long kMaximumMeshElements = 10000000;

class TextSceneReader {
public:
  TextSceneReader(const std::filesystem::path& file, const MoveItRobot& robot) : file_(file), builder_(robot, file) {}

  MoveItProblem read() {
    if (!std::filesystem::is_regular_file(file_)) throw Error("scene file " + file_.string() + " does not exist");
    std::ifstream in(file_);
    std::string line;
    while (std::getline(in, line)) {
      if (!line.empty() && line.back() == '\r') line.pop_back();
      lines_.push_back(line);
    }
    std::string name = trimmed(next("the scene name"));
    if (!name.empty() && name.back() == '+') name.pop_back();  // RViz marks its newer layout so
    if (!name.empty() && name != "(noname)") builder_.setName(name);
    while (true) {
      const std::string text = trimmed(next("'* object' or the closing '.'"));
      if (text == ".") break;
      if (text.empty()) continue;
      if (text.rfind('*', 0) != 0) fail("expected '* object name' or the closing '.', got '" + text + "'");
      readObject(trimmed(text.substr(1)));
    }
    return builder_.finish();
  }

private:
  [[noreturn]] void fail(const std::string& what) const {
    throw Error(file_.string() + ":" + std::to_string(line_) + ": " + what);
  }

  std::string next(const std::string& expected) {
    if (line_ >= lines_.size()) fail("the file ends where " + expected + " was expected (a scene ends with '.')");
    return lines_[line_++];
  }

  static std::string trimmed(const std::string& text) {
    const auto first = text.find_first_not_of(" \t");
    if (first == std::string::npos) return "";
    return text.substr(first, text.find_last_not_of(" \t") - first + 1);
  }

  std::vector<double> numbers(std::size_t count, const std::string& what) {
    const std::string text = next(what);
    std::istringstream words(text);
    std::vector<double> values;
    for (std::string word; words >> word;) {
      const auto value = parseDouble(word);
      if (!value) fail(what + ": '" + word + "' is not a number");
      values.push_back(*value);
    }
    if (values.size() != count) {
      fail(what + ": expected " + std::to_string(count) + " numbers, got " + std::to_string(values.size()));
    }
    return values;
  }

  long long count(const std::string& what, long long maximum) {
    const auto values = numbers(1, what);
    if (values[0] < 0 || values[0] > maximum || values[0] != static_cast<double>(static_cast<long long>(values[0])))
      fail(what + ": expected a whole number between 0 and " + std::to_string(maximum));
    return static_cast<long long>(values[0]);
  }

  Eigen::Isometry3d pose(const std::string& what) {
    const auto position = numbers(3, what + " position [x y z]");
    const auto q = numbers(4, what + " orientation [x y z w]");
    const Eigen::Vector4d xyzw(q[0], q[1], q[2], q[3]);
    if (!(xyzw.norm() > 1e-9)) {
      fail(what + ": quaternion [x y z w] of zero norm is no rotation");
    }
    Eigen::Isometry3d result = Eigen::Isometry3d::Identity();
    result.translation() = Eigen::Vector3d(position[0], position[1], position[2]);
    const Eigen::Vector4d unit = xyzw.normalized();
    result.linear() = Eigen::Quaterniond(unit[3], unit[0], unit[1], unit[2]).matrix();
    return result;
  }

  bool newLayout() const {
    if (line_ >= lines_.size()) return false;
    std::istringstream words(lines_[line_]);
    int count = 0;
    for (std::string word; words >> word;) ++count;
    return count > 1;
  }

  void readObject(const std::string& id) {
    if (id.empty()) fail("an object needs a name after '*'");
    if (!layoutKnown_) {
      newLayout_ = newLayout();
      layoutKnown_ = true;
    }
    const std::size_t at = line_;
    const Eigen::Isometry3d objectPose = newLayout_ ? pose("object '" + id + "'") : Eigen::Isometry3d::Identity();
    const long long shapes = count("object '" + id + "' shape count", kMaximumShapes);
    if (shapes == 0) fail("object '" + id + "' has no shapes");
    std::vector<Obstacle> bodies;
    for (long long k = 0; k < shapes; ++k) {
      Obstacle shape = readShape("object '" + id + "' shape " + std::to_string(k));
      shape.pose = objectPose * pose("object '" + id + "' shape " + std::to_string(k));
      numbers(4, "object '" + id + "' shape " + std::to_string(k) + " colour [r g b a]");
      bodies.push_back(std::move(shape));
    }
    if (newLayout_) {
      const long long subframes = count("object '" + id + "' subframe count", kMaximumShapes);
      for (long long k = 0; k < subframes; ++k) {
        next("a subframe name");
        pose("object '" + id + "' subframe " + std::to_string(k));
      }
    }
    if (!builder_.addObject(id, std::move(bodies), "", {})) {
      line_ = at;
      fail(builder_.problem());
    }
  }

  Obstacle readShape(const std::string& what) {
    const std::string type = trimmed(next(what + " type"));
    Obstacle shape;
    if (type == "box") {
      const auto size = positives(3, what + " box size [x y z]");
      shape.shape = Obstacle::Shape::Box;
      shape.size = Eigen::Vector3d(size[0], size[1], size[2]);
    } else if (type == "sphere") {
      shape.shape = Obstacle::Shape::Sphere;
      shape.radius = positives(1, what + " sphere radius")[0];
    } else if (type == "cylinder") {
      const auto values = positives(2, what + " cylinder [radius length]");
      shape.shape = Obstacle::Shape::Cylinder;
      shape.radius = values[0];
      shape.length = values[1];
    } else if (type == "cone") {
      const auto values = positives(2, what + " cone [radius length]");
      shape.shape = Obstacle::Shape::Mesh;
      shape.meshData = std::make_shared<const robot::TriangleMesh>(detail::coneMesh(values[1], values[0]));
    } else if (type == "mesh") {
      shape.shape = Obstacle::Shape::Mesh;
      shape.meshData = std::make_shared<const robot::TriangleMesh>(readMesh(what));
    } else {
      fail(what + ": unknown shape type '" + type + "'; expected box, sphere, cylinder, cone or mesh");
    }
    return shape;
  }

  std::vector<double> positives(std::size_t n, const std::string& what) {
    const auto values = numbers(n, what);
    for (const double value : values) {
      if (!(value > 0.0)) {
        fail(what + ": sizes must be positive");
      }
    }
    return values;
  }

  robot::TriangleMesh readMesh(const std::string& what) {
    const auto counts = numbers(2, what + " mesh [vertex count, triangle count]");
    for (const double c : counts) {
      if (c < 1 || c > kMaximumMeshElements || c != static_cast<double>(static_cast<long long>(c))) {
        fail(what + ": mesh counts must be whole numbers between 1 and " + std::to_string(kMaximumMeshElements));
      }
    }
    robot::TriangleMesh mesh;
    const auto vertexCount = static_cast<long long>(counts[0]), triangleCount = static_cast<long long>(counts[1]);
    for (long long i = 0; i < vertexCount; ++i) {
      const auto v = numbers(3, what + " vertex " + std::to_string(i));
      mesh.vertices.emplace_back(v[0], v[1], v[2]);
    }
    for (long long i = 0; i < triangleCount; ++i) {
      const auto t = numbers(3, what + " triangle " + std::to_string(i));
      for (const double index : t) {
        if (index < 0 || index >= static_cast<double>(vertexCount) ||
            index != static_cast<double>(static_cast<long long>(index))) {
          fail(what + " triangle " + std::to_string(i) + ": vertex indices must be whole numbers below " +
               std::to_string(vertexCount));
        }
      }
      mesh.triangles.emplace_back(static_cast<int>(t[0]), static_cast<int>(t[1]), static_cast<int>(t[2]));
    }
    return mesh;
  }

  std::filesystem::path file_;
  detail::SceneBuilder builder_;
  std::vector<std::string> lines_;
  std::size_t line_ = 0;  // lines read so far = the 1-based number of the last one read
  bool layoutKnown_ = false, newLayout_ = false;
};

}  // namespace

MoveItProblem loadMoveItTextScene(const std::filesystem::path& sceneFile, const MoveItRobot& robot) {
  return TextSceneReader(sceneFile, robot).read();
}

}  // namespace arcplan::collision
