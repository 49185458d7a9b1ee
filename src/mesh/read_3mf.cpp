// SPDX-License-Identifier: GPL-3.0-or-later
//! read_3mf(): the 3MF reader of read_mesh() (3MF Core Specification 1.3).
//! A 3MF file is a zip (opened in memory with libzip) whose root model part
//! (named by _rels/.rels, usually 3D/3dmodel.model) is XML (parsed by expat,
//! streamed): <resources> holds <object>s, each a <mesh> (<vertices><vertex
//! x y z/>..., <triangles><triangle v1 v2 v3/>...) or <components> (<component
//! objectid transform/>, possibly in another model part: production
//! extension p:path); <build> lists the <item objectid transform/>s to make.
//! The result is every build item's mesh, transformed to the build's frame,
//! in millimetres (the <model unit> converted), as one triangle soup.
//! Support objects (type "support", "solidsupport") are skipped, said so.
#include <zip.h>
#include <expat.h>

#include <array>
#include <climits>
#include <cmath>
#include <cstring>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "mesh/mesh_readers.h"

namespace subfab::detail {

namespace {

//! 3MF affine transform "m00 m01 m02 m10 m11 m12 m20 m21 m22 m30 m31 m32":
//! a point is a row vector, p' = p * M (the last row is the translation).
struct Transform {
  std::array<double, 12> m = {1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
  Vec3 apply(const Vec3& p) const {
    return {p.x() * m[0] + p.y() * m[3] + p.z() * m[6] + m[9], p.x() * m[1] + p.y() * m[4] + p.z() * m[7] + m[10],
            p.x() * m[2] + p.y() * m[5] + p.z() * m[8] + m[11]};
  }
  //! this first, then `after`.
  Transform then(const Transform& after) const {
    Transform r;
    for (int row = 0; row < 4; ++row)
      for (int col = 0; col < 3; ++col) {
        double s = row == 3 ? after.m[static_cast<std::size_t>(9 + col)] : 0.0;
        for (int k = 0; k < 3; ++k)
          s += m[static_cast<std::size_t>(row * 3 + k)] * after.m[static_cast<std::size_t>(k * 3 + col)];
        r.m[static_cast<std::size_t>(row * 3 + col)] = s;
      }
    return r;
  }
  double determinant() const {
    return m[0] * (m[4] * m[8] - m[5] * m[7]) - m[1] * (m[3] * m[8] - m[5] * m[6]) +
           m[2] * (m[3] * m[7] - m[4] * m[6]);
  }
};

struct Component {
  std::int64_t object_id = 0;
  std::string part;  // model part holding the object ("" = the same part)
  Transform transform;
  std::size_t line = 0;
};

struct Object {
  std::string type = "model";
  std::vector<Vec3> vertices;
  std::vector<Triangle> triangles;
  std::vector<Component> components;
  std::size_t line = 0;
};

//! One parsed model part.
struct ModelPart {
  double to_millimetres = 1;
  std::string unit = "millimeter";
  std::map<std::int64_t, Object> objects;
  std::vector<Component> build;  // the <item>s (root part only)
};

//! Element name without its namespace prefix ("m:vertex" -> "vertex").
std::string_view local_name(const XML_Char* name) {
  std::string_view s(name);
  const auto colon = s.rfind(':');
  return colon == std::string_view::npos ? s : s.substr(colon + 1);
}

const XML_Char* attribute(const XML_Char** attributes, std::string_view wanted) {
  for (std::size_t i = 0; attributes[i]; i += 2)
    if (local_name(attributes[i]) == wanted) return attributes[i + 1];
  return nullptr;
}

//! Opens the zip held in memory; closes it on destruction.
class ZipArchive {
 public:
  ZipArchive(std::string_view data, const std::string& name) : name_(name) {
    zip_error_t error;
    zip_error_init(&error);
    zip_source_t* source = zip_source_buffer_create(data.data(), data.size(), 0, &error);
    if (source) archive_ = zip_open_from_source(source, ZIP_RDONLY, &error);
    if (!archive_) {
      const std::string why = zip_error_strerror(&error);
      zip_error_fini(&error);
      if (source) zip_source_free(source);
      throw_io(name_, {}, "not a 3MF file: it is not a readable zip archive (" + why +
                              "); a .3mf file is the zip a slicer or CAD program saves");
    }
    zip_error_fini(&error);
  }
  ~ZipArchive() {
    if (archive_) zip_discard(archive_);
  }
  ZipArchive(const ZipArchive&) = delete;
  ZipArchive& operator=(const ZipArchive&) = delete;

  //! Index of the entry `path` (leading '/' ignored, case-insensitive), if any.
  std::optional<zip_uint64_t> find(std::string path) const {
    while (!path.empty() && path.front() == '/') path.erase(0, 1);
    const zip_int64_t i = zip_name_locate(archive_, path.c_str(), ZIP_FL_NOCASE);
    if (i < 0) return std::nullopt;
    return static_cast<zip_uint64_t>(i);
  }

  //! Streams the entry's bytes to `consume(const char*, size, bool last)`.
  template <class F>
  void read(zip_uint64_t index, const std::string& path, F&& consume) const {
    std::unique_ptr<zip_file_t, int (*)(zip_file_t*)> file(zip_fopen_index(archive_, index, 0), zip_fclose);
    if (!file)
      throw_io(name_, {}, "cannot read '" + path + "' in the archive: " + zip_strerror(archive_));
    std::vector<char> buffer(1 << 16);
    while (true) {
      const zip_int64_t n = zip_fread(file.get(), buffer.data(), buffer.size());
      if (n < 0)
        throw_io(name_, {}, "cannot read '" + path + "' in the archive (corrupt zip?): " +
                                zip_file_strerror(file.get()));
      consume(buffer.data(), static_cast<std::size_t>(n), n == 0);
      if (n == 0) break;
    }
  }

 private:
  std::string name_;
  zip_t* archive_ = nullptr;
};

//! Parses one model part with expat (callbacks below).
class ModelParser {
 public:
  ModelParser(const std::string& where, ModelPart& part) : where_(where), part_(part) {
    parser_ = XML_ParserCreate(nullptr);
    if (!parser_) throw IoError(where_ + ": out of memory creating the XML parser");
    XML_SetUserData(parser_, this);
    XML_SetElementHandler(parser_, &ModelParser::on_start, &ModelParser::on_end);
  }
  ~ModelParser() { XML_ParserFree(parser_); }
  ModelParser(const ModelParser&) = delete;
  ModelParser& operator=(const ModelParser&) = delete;

  void feed(const char* data, std::size_t size, bool last) {
    if (XML_Parse(parser_, data, static_cast<int>(size), last ? 1 : 0) == XML_STATUS_ERROR) {
      if (error_) std::rethrow_exception(error_);
      throw_io(where_, Location::line(XML_GetCurrentLineNumber(parser_)),
               std::string("malformed XML: ") + XML_ErrorString(XML_GetErrorCode(parser_)));
    }
    if (last && !saw_model_) throw_io(where_, {}, "no <model> element: this part is not a 3MF model");
  }

 private:
  static void on_start(void* self, const XML_Char* name, const XML_Char** attributes) {
    auto* p = static_cast<ModelParser*>(self);
    try {
      p->start(local_name(name), attributes);
    } catch (...) {
      p->error_ = std::current_exception();
      XML_StopParser(p->parser_, XML_FALSE);
    }
  }
  static void on_end(void* self, const XML_Char* name) {
    auto* p = static_cast<ModelParser*>(self);
    if (local_name(name) == "object") p->object_ = nullptr;
  }

  std::size_t line() const { return XML_GetCurrentLineNumber(parser_); }
  [[noreturn]] void fail(const std::string& what) const { throw_io(where_, Location::line(line()), what); }
  [[noreturn]] void fail_invalid(const std::string& what) const {
    throw_invalid(where_, Location::line(line()), what);
  }

  //! Required attribute `key` of element `element`.
  const XML_Char* required(const XML_Char** attributes, std::string_view element, std::string_view key) const {
    const XML_Char* value = attribute(attributes, key);
    if (!value) fail("<" + std::string(element) + "> without its '" + std::string(key) + "' attribute");
    return value;
  }

  double number(const XML_Char* text, std::string_view what) const {
    const char* p = text;
    const char* end = text + std::strlen(text);
    while (p < end && is_space_or_newline(*p)) ++p;
    double v = 0;
    if (!parse_double(p, end, v)) fail(std::string(what) + " is not a number: '" + printable(text) + "'");
    while (p < end && is_space_or_newline(*p)) ++p;
    if (p != end) fail(std::string(what) + " is not a number: '" + printable(text) + "'");
    if (!std::isfinite(v)) fail_invalid(std::string(what) + " is not finite (" + printable(text) + "); fix or remove it");
    return v;
  }

  std::int64_t integer(const XML_Char* text, std::string_view what) const {
    const char* p = text;
    const char* end = text + std::strlen(text);
    std::int64_t v = 0;
    if (!parse_int(p, end, v) || p != end) fail(std::string(what) + " is not an integer: '" + printable(text) + "'");
    return v;
  }

  Transform transform(const XML_Char** attributes) const {
    Transform t;
    const XML_Char* text = attribute(attributes, "transform");
    if (!text) return t;
    const char* p = text;
    const char* end = text + std::strlen(text);
    for (double& v : t.m) {
      while (p < end && is_space_or_newline(*p)) ++p;
      if (!parse_double(p, end, v) || !std::isfinite(v))
        fail("transform '" + printable(text) + "' is not 12 finite numbers");
    }
    while (p < end && is_space_or_newline(*p)) ++p;
    if (p != end) fail("transform '" + printable(text) + "' has more than 12 numbers");
    return t;
  }

  Component reference(const XML_Char** attributes, std::string_view element) const {
    Component c;
    c.object_id = integer(required(attributes, element, "objectid"), "objectid");
    if (const XML_Char* path = attribute(attributes, "path")) c.part = path;  // p:path (production extension)
    c.transform = transform(attributes);
    c.line = line();
    return c;
  }

  void start(std::string_view element, const XML_Char** attributes) {
    if (element == "model") {
      saw_model_ = true;
      if (const XML_Char* unit = attribute(attributes, "unit")) {
        static const std::map<std::string, double, std::less<>> units = {
            {"micron", 0.001}, {"millimeter", 1}, {"centimeter", 10}, {"inch", 25.4}, {"foot", 304.8}, {"meter", 1000}};
        const auto it = units.find(std::string_view(unit));
        if (it == units.end())
          fail("unknown unit '" + printable(unit) + "' (3MF allows micron, millimeter, centimeter, inch, foot, meter)");
        part_.unit = it->first;
        part_.to_millimetres = it->second;
      }
    } else if (element == "object") {
      const std::int64_t id = integer(required(attributes, element, "id"), "object id");
      auto [it, inserted] = part_.objects.try_emplace(id);
      if (!inserted) fail("two objects with id " + std::to_string(id));
      object_ = &it->second;
      object_->line = line();
      if (const XML_Char* type = attribute(attributes, "type")) object_->type = type;
    } else if (element == "vertex") {
      if (!object_) fail("<vertex> outside an <object>");
      const double x = number(required(attributes, element, "x"), "vertex x");
      const double y = number(required(attributes, element, "y"), "vertex y");
      const double z = number(required(attributes, element, "z"), "vertex z");
      object_->vertices.emplace_back(x, y, z);
    } else if (element == "triangle") {
      if (!object_) fail("<triangle> outside an <object>");
      Triangle t;
      const char* keys[3] = {"v1", "v2", "v3"};
      for (int k = 0; k < 3; ++k) {
        const std::int64_t v = integer(required(attributes, element, keys[k]), keys[k]);
        if (v < 0 || static_cast<std::uint64_t>(v) >= object_->vertices.size())
          fail_invalid("triangle " + std::to_string(object_->triangles.size()) + ": " + keys[k] + " = " +
                       std::to_string(v) + " is out of range (the object has " +
                       std::to_string(object_->vertices.size()) + " vertices, indices 0.." +
                       std::to_string(static_cast<std::int64_t>(object_->vertices.size()) - 1) + ")");
        t[static_cast<std::size_t>(k)] = static_cast<int>(v);
      }
      object_->triangles.push_back(t);
    } else if (element == "component") {
      if (!object_) fail("<component> outside an <object>");
      object_->components.push_back(reference(attributes, element));
    } else if (element == "item") {
      part_.build.push_back(reference(attributes, element));
    }
  }

  std::string where_;
  ModelPart& part_;
  XML_Parser parser_ = nullptr;
  Object* object_ = nullptr;
  bool saw_model_ = false;
  std::exception_ptr error_;
};

//! Reads the model parts on demand and flattens the build into one mesh.
class Assembler {
 public:
  Assembler(const ZipArchive& zip, const std::string& name, Mesh& mesh, ReadInfo& info)
      : zip_(zip), name_(name), mesh_(mesh), info_(info) {}

  const ModelPart& part(const std::string& path) {
    std::string key = path;
    while (!key.empty() && key.front() == '/') key.erase(0, 1);
    if (auto it = parts_.find(key); it != parts_.end()) return it->second;
    const auto index = zip_.find(key);
    if (!index)
      throw_io(name_, {},
               parts_.empty() ? "the archive has no 3D model ('" + key +
                                    "' is missing): not a 3MF file, or a 3MF file without a model"
                              : "a component refers to the model part '" + key + "', which the archive does not have");
    ModelPart& part = parts_[key];
    ModelParser parser(name_ + " (" + key + ")", part);
    zip_.read(*index, key, [&](const char* d, std::size_t n, bool last) { parser.feed(d, n, last); });
    return part;
  }

  void add(const std::string& path, const Component& ref, const Transform& to_root, int depth) {
    const std::string key = ref.part.empty() ? path : ref.part;
    const ModelPart& p = part(key);
    const std::string where = name_ + " (" + key + ")";
    const auto it = p.objects.find(ref.object_id);
    if (it == p.objects.end())
      throw_io(where, Location::line(ref.line), "refers to object " + std::to_string(ref.object_id) +
                                                   ", which the model does not define");
    if (depth > 32)
      throw_io(where, Location::line(ref.line), "components nested more than 32 deep (a component cycle?)");
    const Object& object = it->second;
    if (object.type == "support" || object.type == "solidsupport") {
      ++skipped_supports_;
      return;
    }
    const Transform t = ref.transform.then(to_root);
    if (!object.triangles.empty()) {
      const bool mirrored = t.determinant() < 0;  // keep the faces outward
      const auto base = mesh_.vertices.size();
      if (base + object.vertices.size() > static_cast<std::size_t>(INT_MAX))
        throw_invalid(name_, {}, "too many vertices");
      for (const Vec3& v : object.vertices) mesh_.vertices.push_back(t.apply(v) * to_millimetres_);
      for (const Triangle& tri : object.triangles) {
        const int b = static_cast<int>(base);
        mesh_.faces.push_back(mirrored ? Triangle{tri[0] + b, tri[2] + b, tri[1] + b}
                                       : Triangle{tri[0] + b, tri[1] + b, tri[2] + b});
      }
      info_.vertices_in_file += object.vertices.size();
      info_.polygons_in_file += object.triangles.size();
    }
    for (const Component& c : object.components) add(key, c, t, depth + 1);
  }

  std::size_t skipped_supports_ = 0;
  double to_millimetres_ = 1;  // the root part's unit (3MF: it applies to the whole build)

 private:
  const ZipArchive& zip_;
  const std::string& name_;
  Mesh& mesh_;
  ReadInfo& info_;
  std::map<std::string, ModelPart> parts_;
};

//! The root model part named by _rels/.rels (3MF: the relationship of type
//! .../3dmodel), or the conventional 3D/3dmodel.model.
std::string root_model_path(const ZipArchive& zip, const std::string& name) {
  const std::string fallback = "3D/3dmodel.model";
  const auto rels = zip.find("_rels/.rels");
  if (!rels) return fallback;
  struct State {
    std::string target;
  } state;
  XML_Parser parser = XML_ParserCreate(nullptr);
  if (!parser) return fallback;
  XML_SetUserData(parser, &state);
  XML_SetStartElementHandler(parser, [](void* user, const XML_Char* element, const XML_Char** attributes) {
    auto* s = static_cast<State*>(user);
    if (local_name(element) != "Relationship" || !s->target.empty()) return;
    const XML_Char* type = attribute(attributes, "Type");
    const XML_Char* target = attribute(attributes, "Target");
    if (type && target && std::string_view(type).ends_with("/3dmodel")) s->target = target;
  });
  bool ok = true;
  zip.read(*rels, "_rels/.rels", [&](const char* d, std::size_t n, bool last) {
    if (ok && XML_Parse(parser, d, static_cast<int>(n), last ? 1 : 0) == XML_STATUS_ERROR) ok = false;
  });
  XML_ParserFree(parser);
  return state.target.empty() ? fallback : state.target;  // unreadable .rels: try the usual place
}

}  // namespace

void read_3mf(std::string_view data, const std::string& name, Mesh& mesh, ReadInfo& info) {
  const ZipArchive zip(data, name);
  const std::string root = root_model_path(zip, name);
  Assembler assembler(zip, name, mesh, info);
  const ModelPart& model = assembler.part(root);
  assembler.to_millimetres_ = model.to_millimetres;
  if (model.build.empty()) throw_invalid(name, {}, "the 3MF model has no <build> item: nothing to make");
  for (const Component& item : model.build) assembler.add(root, item, Transform{}, 0);
  if (model.unit != "millimeter")
    info.notes.push_back("3MF unit '" + model.unit + "' converted to millimetres");
  if (model.build.size() > 1)
    info.notes.push_back(std::to_string(model.build.size()) + " build items read as one mesh");
  if (assembler.skipped_supports_ > 0)
    info.notes.push_back("skipped " + std::to_string(assembler.skipped_supports_) + " support objects");
}

}  // namespace subfab::detail
