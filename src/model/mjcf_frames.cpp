// MuJoCo 3.x <frame> and <replicate>: replaced by their children with the pose composed in.

#include <cmath>

#include "mjcf_detail.hpp"

namespace mjarm::mjcf_detail {

namespace {

// marks the frames a <replicate> expands into (never written out: frames are expanded next)
constexpr const char* kFromReplicate = "mjarm-replicate";

bool is_identity(const Vec3& p, const Quat& q) {
  return p == Vec3{0, 0, 0} && std::abs(std::abs(q[0]) - 1) < 1e-15;
}

bool uses_class(std::string_view tag) {
  return tag == "geom" || tag == "site" || tag == "joint" || tag == "camera" || tag == "light";
}

// class an element of the body tree reads its defaults from
std::string class_of(const XmlNode& c, const std::string& childclass) {
  if (const std::string* cls = c.find("class")) return *cls;
  return childclass.empty() ? std::string("main") : childclass;
}

Vec3 vec3_or(const XmlNode& n, const char* key, const std::optional<std::string>& fallback,
             Vec3 otherwise) {
  std::vector<double> v = n.has(key) ? numbers(n, key)
                          : fallback ? parse_numbers(n, key, *fallback)
                                     : std::vector<double>{};
  if (v.empty()) return otherwise;
  if (v.size() != 3) fail(n, std::string(key) + " needs 3 numbers");
  return {v[0], v[1], v[2]};
}

std::string format_vec(const Vec3& v) { return format_numbers(v); }
std::string format_quat(const Quat& q) { return format_numbers(q); }

// compose the pose (p, q) of an enclosing frame into child element c
void compose(XmlNode& c, const Vec3& p, const Quat& q, const std::string& cls, const Context& ctx,
             const Defaults& defaults) {
  const std::string_view tag = c.tag;
  const bool has_defaults = uses_class(tag);
  auto dflt = [&](const char* attr) -> std::optional<std::string> {
    return has_defaults ? defaults.lookup(cls, default_kind(tag), attr) : std::nullopt;
  };
  auto place = [&](const Vec3& v) {
    const Vec3 r = quat_rotate(q, v);
    return Vec3{p[0] + r[0], p[1] + r[1], p[2] + r[2]};
  };

  if (tag == "freejoint") return;
  if (tag == "joint") {
    c.set("pos", format_vec(place(vec3_or(c, "pos", dflt("pos"), {0, 0, 0}))));
    c.set("axis", format_vec(quat_rotate(q, vec3_or(c, "axis", dflt("axis"), {0, 0, 1}))));
    return;
  }
  if (tag == "light") {
    c.set("pos", format_vec(place(vec3_or(c, "pos", dflt("pos"), {0, 0, 0}))));
    c.set("dir", format_vec(quat_rotate(q, vec3_or(c, "dir", dflt("dir"), {0, 0, -1}))));
    return;
  }
  if (tag != "body" && tag != "frame" && tag != "geom" && tag != "site" && tag != "camera" &&
      tag != "inertial") {
    fail(c, "cannot be placed inside a <frame>/<replicate> that has a pose");
  }

  // fromto (geom, site) wins over pos/orientation: resolve it in the frame, as MuJoCo does in a
  // body (midpoint, minimal rotation of z onto from - to, half length as the last size)
  if (c.has("fromto")) {
    const std::vector<double> v = numbers(c, "fromto");
    if (v.size() != 6) fail(c, "fromto needs 6 numbers");
    const Vec3 axis{v[0] - v[3], v[1] - v[4], v[2] - v[5]};
    const double length = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
    const std::string* own_type = c.find("type");
    const std::string type = own_type ? *own_type : dflt("type").value_or("sphere");
    const std::size_t half = type == "capsule" || type == "cylinder" ? 1
                             : type == "box" || type == "ellipsoid"  ? 2
                                                                     : 0;
    if (half == 0 || length < 1e-12) fail(c, "fromto with type \"" + type + "\" in a frame");
    const std::string* own_size = c.find("size");
    const auto size_text = own_size ? std::optional(*own_size) : dflt("size");
    std::vector<double> size =
        size_text ? parse_numbers(c, "size", *size_text) : std::vector<double>{};
    if (size.size() < half) fail(c, "fromto needs the size of the cross-section");
    size.resize(half + 1);
    size[half] = length / 2;
    XmlNode dir;
    dir.set("zaxis", format_vec(axis));
    const Quat own = *read_orientation(dir, ctx);
    c.erase("fromto");
    erase_orientation(c);
    c.set("size", format_numbers(size));
    c.set("pos", format_vec(place({(v[0] + v[3]) / 2, (v[1] + v[4]) / 2, (v[2] + v[5]) / 2})));
    c.set("quat", format_quat(quat_mul(q, own)));
    return;
  }
  if (dflt("fromto")) fail(c, "its default class sets fromto; cannot compose a frame pose into it");

  c.set("pos", format_vec(place(vec3_or(c, "pos", dflt("pos"), {0, 0, 0}))));
  Quat own{1, 0, 0, 0};
  if (const auto o = read_orientation(c, ctx)) {
    own = *o;
  } else if (has_defaults) {
    for (const char* alt : {"axisangle", "xyaxes", "zaxis", "euler"}) {
      // 2.2.2 lets a default's alternative orientation override an element's quat
      if (dflt(alt))
        fail(c, std::string("its default class sets ") + alt +
                    "; cannot compose a frame pose into it");
    }
    if (const auto dq = dflt("quat")) {
      const std::vector<double> v = parse_numbers(c, "quat", *dq);
      if (v.size() != 4) fail(c, "default quat needs 4 numbers");
      XmlNode tmp = c;
      tmp.set("quat", *dq);
      own = *read_orientation(tmp, ctx);
    }
  }
  erase_orientation(c);
  c.set("quat", format_quat(quat_mul(q, own)));
}

// moves the children of `frame` (pose p, q relative to the enclosing body) into `out`
void splice(XmlNode& frame, const Vec3& p, const Quat& q, const std::string& outer_childclass,
            std::vector<XmlNode>& out, Context& ctx, const Defaults& defaults) {
  const std::string* own_cc = frame.find("childclass");
  const std::string cc = own_cc ? *own_cc : outer_childclass;
  const bool identity = is_identity(p, q);
  for (auto& c : frame.children) {
    // a frame childclass reaches its children explicitly once the frame is gone
    if (own_cc) {
      if (uses_class(c.tag) && !c.has("class")) c.set("class", *own_cc);
      if ((c.tag == "body" || c.tag == "frame") && !c.has("childclass")) {
        c.set("childclass", *own_cc);
      }
    }
    if (c.tag == "frame") {
      // a nested frame's pose is relative to this one
      const Vec3 pc = vec3_or(c, "pos", std::nullopt, {0, 0, 0});
      const Quat qc = read_orientation(c, ctx).value_or(Quat{1, 0, 0, 0});
      const Vec3 r = quat_rotate(q, pc);
      splice(c, {p[0] + r[0], p[1] + r[1], p[2] + r[2]}, quat_mul(q, qc), cc, out, ctx, defaults);
      continue;
    }
    if (!identity) compose(c, p, q, class_of(c, cc), ctx, defaults);
    out.push_back(std::move(c));
  }
}

void expand_in(XmlNode& body, const std::string& inherited_cc, Context& ctx,
               const Defaults& defaults) {
  const std::string* own = body.tag == "body" ? body.find("childclass") : nullptr;
  const std::string cc = own ? *own : inherited_cc;
  std::vector<XmlNode> out;
  out.reserve(body.children.size());
  for (auto& c : body.children) {
    if (c.tag != "frame") {
      out.push_back(std::move(c));
      continue;
    }
    const std::size_t before = out.size();
    const Vec3 p = vec3_or(c, "pos", std::nullopt, {0, 0, 0});
    const Quat q = read_orientation(c, ctx).value_or(Quat{1, 0, 0, 0});
    splice(c, p, q, cc, out, ctx, defaults);
    // frames made from a <replicate> were reported with it
    if (c.has(kFromReplicate)) continue;
    ctx.warn(c, "<frame> is MuJoCo 3.x; its " + std::to_string(out.size() - before) +
                    " element(s) were moved into the enclosing body with the frame pose "
                    "composed into them");
  }
  body.children = std::move(out);
  for (auto& c : body.children) {
    if (c.tag == "body") expand_in(c, cc, ctx, defaults);
  }
}

bool has_named_descendant(const XmlNode& n) {
  for (const auto& c : n.children) {
    if (c.has("name") || has_named_descendant(c)) return true;
  }
  return false;
}

// replaces each <replicate> below `parent` (deepest first) by `count` frames
void replicate_in(XmlNode& parent, Context& ctx) {
  for (auto& c : parent.children) replicate_in(c, ctx);
  std::vector<XmlNode> out;
  for (auto& c : parent.children) {
    if (c.tag != "replicate") {
      out.push_back(std::move(c));
      continue;
    }
    const std::vector<double> count = numbers(c, "count");
    if (count.size() != 1 || count[0] < 1 || count[0] != std::floor(count[0])) {
      fail(c, "count must be a positive integer");
    }
    if (has_named_descendant(c)) {
      fail(c,
           "replicated elements carry names: the 3.x name-suffix scheme is not reproduced; "
           "expand this <replicate> by hand");
    }
    for (const auto& child : c.children) {
      if (child.tag != "body" && child.tag != "frame" && child.tag != "geom" &&
          child.tag != "site" && child.tag != "camera" && child.tag != "light") {
        fail(child,
             "<replicate> content other than body/frame/geom/site/camera/light is not "
             "translated");
      }
    }
    const Vec3 offset = vec3_or(c, "offset", std::nullopt, {0, 0, 0});
    const Vec3 euler = vec3_or(c, "euler", std::nullopt, {0, 0, 0});
    if (offset != Vec3{0, 0, 0} && euler != Vec3{0, 0, 0}) {
      fail(c,
           "a <replicate> with both offset and euler is not translated (its accumulated pose "
           "convention is not reproduced)");
    }
    const int n = static_cast<int>(count[0]);
    for (int i = 0; i < n; ++i) {
      XmlNode frame;
      frame.tag = "frame";
      frame.line = c.line;
      frame.file = c.file;
      frame.set(kFromReplicate, "1");
      frame.set("pos", format_vec({i * offset[0], i * offset[1], i * offset[2]}));
      frame.set("euler", format_vec({i * euler[0], i * euler[1], i * euler[2]}));
      if (const std::string* cc = c.find("childclass")) frame.set("childclass", *cc);
      frame.children = c.children;
      out.push_back(std::move(frame));
    }
    ctx.warn(c, "<replicate> is MuJoCo 3.x; expanded into " + std::to_string(n) + " copies");
  }
  parent.children = std::move(out);
}

}  // namespace

void expand_replicates(XmlNode& root, Context& ctx, const Defaults& /*defaults*/) {
  for (auto& c : root.children) {
    if (c.tag == "worldbody") replicate_in(c, ctx);
  }
}

void expand_frames(XmlNode& root, Context& ctx, const Defaults& defaults) {
  for (auto& c : root.children) {
    if (c.tag == "worldbody") expand_in(c, "", ctx, defaults);
  }
}

}  // namespace mjarm::mjcf_detail
