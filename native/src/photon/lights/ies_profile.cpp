#include "photon/lights/ies_profile.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>

namespace photon {
namespace {

// Candela to the W/sr per strength watt of Cycles' lamps: 4 pi / 177.83 lm/W.
constexpr double kCandelaToCycles = 0.0706650768394;

// Files with more angles than this are not photometric tables.
constexpr long kMaxAngles = 10000;
constexpr size_t kMaxValues = size_t(1) << 22;

// Numbers of an LM-63 text after its TILT line, commas read as spaces.
class Numbers {
 public:
  Numbers(std::string_view text, size_t start) : text_(text.substr(start)) {
    std::replace(text_.begin(), text_.end(), ',', ' ');
    pos_ = text_.c_str();
  }
  double next() {
    if (failed_) return 0.0;
    char* end = nullptr;
    const double v = std::strtod(pos_, &end);
    if (end == pos_ || !std::isfinite(v)) {
      failed_ = true;
      return 0.0;
    }
    pos_ = end;
    return v;
  }
  long next_integer() {
    const double v = next();
    if (v != std::floor(v) || std::fabs(v) > 1e9) failed_ = true;
    return failed_ ? 0 : static_cast<long>(v);
  }
  bool failed() const { return failed_; }
  void skip_line() {
    const char* nl = std::strchr(pos_, '\n');
    pos_ = nl ? nl + 1 : pos_ + std::strlen(pos_);
  }

 private:
  std::string text_;
  const char* pos_;
  bool failed_ = false;
};

bool angle_close(float a, float b) {
  return std::fabs(a - b) < 1e-4f;
}

float catmull_rom(float a, float b, float c, float d, float x) {
  return 0.5f *
             (((d + 3.0f * (b - c) - a) * x + (2.0f * a - 5.0f * b + 4.0f * c - d)) * x + (c - a)) *
             x +
         b;
}

using Table = std::vector<std::vector<float>>;  // [h][v]

// Types A and B are brought to type C's angles (Cycles' conventions: users rotate the lamp for
// the rest); one quadrant or half of a type C circle is mirrored to the whole.
void to_type_c(int type, std::vector<float>& h, std::vector<float>& v, Table& t) {
  if (type == 2) {  // B: the polar axis is horizontal; transpose and treat as A/C
    Table transposed(v.size(), std::vector<float>(h.size()));
    for (size_t i = 0; i < h.size(); ++i)
      for (size_t j = 0; j < v.size(); ++j) transposed[j][i] = t[i][j];
    t.swap(transposed);
    h.swap(v);
    if (angle_close(h[0], 0.0f)) {  // 0..90: mirror to -90..90, then shift to 0..180
      std::vector<float> nh;
      Table nt;
      for (size_t i = h.size() - 1; i > 0; --i) nh.push_back(90.0f - h[i]), nt.push_back(t[i]);
      for (size_t i = 0; i < h.size(); ++i) nh.push_back(90.0f + h[i]), nt.push_back(t[i]);
      h.swap(nh);
      t.swap(nt);
    } else {
      for (float& a : h) a += 90.0f;
    }
    if (angle_close(v[0], 0.0f)) {
      std::vector<float> nv;
      for (size_t j = v.size() - 1; j > 0; --j) nv.push_back(90.0f - v[j]);
      for (float a : v) nv.push_back(90.0f + a);
      for (auto& row : t) {
        std::vector<float> r;
        for (size_t j = row.size() - 1; j > 0; --j) r.push_back(row[j]);
        r.insert(r.end(), row.begin(), row.end());
        row.swap(r);
      }
      v.swap(nv);
    } else {
      for (float& a : v) a += 90.0f;
    }
    return;
  }
  if (type == 3) {  // A: -90..90 maps to 270..90 of type C
    for (float& a : v) a += 90.0f;
    std::vector<float> nh;
    Table nt;
    for (size_t i = h.size(); i-- > 0;) nh.push_back(180.0f - h[i]), nt.push_back(t[i]);
    if (angle_close(h[0], 0.0f))
      for (size_t i = 1; i < h.size(); ++i) nh.push_back(180.0f + h[i]), nt.push_back(t[i]);
    h.swap(nh);
    t.swap(nt);
    return;
  }
  // C
  if (angle_close(h[0], 90.0f))  // stored from 90 to 270
    for (float& a : h) a -= 90.0f;
  if (h.size() == 1) {  // rotationally symmetric
    h[0] = 0.0f;
    h.push_back(360.0f);
    t.push_back(t[0]);
  }
  if (angle_close(h.back(), 90.0f)) {  // one quadrant: first mirror to two
    for (size_t i = h.size() - 1; i-- > 0;) h.push_back(180.0f - h[i]), t.push_back(t[i]);
  }
  if (angle_close(h.back(), 180.0f)) {  // one half: mirror to the whole
    for (size_t i = h.size() - 1; i-- > 0;) h.push_back(360.0f - h[i]), t.push_back(t[i]);
  }
  if (angle_close(h[0], 0.0f) && !angle_close(h.back(), 360.0f) && h.size() >= 2) {
    // Files that leave out the 360 degree entry, equal to 0's, when their spacing says so.
    const float gap = 360.0f - h.back();
    if (angle_close(h[h.size() - 1] - h[h.size() - 2], gap) || angle_close(h[1] - h[0], gap)) {
      h.push_back(360.0f);
      t.push_back(t[0]);
    }
  }
}

bool increasing(const std::vector<float>& a) {
  for (size_t i = 1; i < a.size(); ++i)
    if (!(a[i] > a[i - 1])) return false;
  return true;
}

}  // namespace

std::optional<IesProfile> IesProfile::parse(std::string_view text, std::string* error,
                                            IesEdges edges) {
  auto fail = [&](const char* why) {
    if (error) *error = why;
    return std::nullopt;
  };
  // The keyword lines end at the TILT line; the numbers follow it.
  size_t tilt = text.rfind("TILT=", 0) == 0 ? 0 : text.find("\nTILT=");
  if (tilt == std::string_view::npos) return fail("no TILT= line: not an IES LM-63 file");
  if (text[tilt] == '\n') ++tilt;
  const bool tilt_include = text.substr(tilt).rfind("TILT=INCLUDE", 0) == 0;
  Numbers n(text, tilt + (tilt_include ? std::strlen("TILT=INCLUDE") : 0));
  if (tilt_include) {
    n.next();  // lamp-to-luminaire geometry
    const long count = n.next_integer();
    if (count < 0 || count > kMaxAngles) return fail("its tilt table is malformed");
    for (long i = 0; i < 2 * count; ++i) n.next();
  } else {
    n.skip_line();  // TILT=NONE, or a tilt file Cycles does not read either
  }
  n.next_integer();  // number of lamps
  n.next();          // lumens per lamp
  double factor = n.next();
  const long v_count = n.next_integer();
  const long h_count = n.next_integer();
  const long type = n.next_integer();
  n.next_integer();              // units
  n.next(), n.next(), n.next();  // width, length, height
  factor *= n.next();            // ballast factor
  factor *= n.next();            // ballast-lamp photometric factor
  n.next();                      // input watts
  if (n.failed()) return fail("its header ends early or holds something other than numbers");
  if (type < 1 || type > 3) return fail("its photometric type is not A, B or C");
  if (v_count < 1 || h_count < 1 || v_count > kMaxAngles || h_count > kMaxAngles ||
      size_t(v_count) * size_t(h_count) > kMaxValues)
    return fail("its numbers of angles are out of range");
  factor *= kCandelaToCycles;

  std::vector<float> v(v_count), h(h_count);
  for (float& a : v) a = static_cast<float>(n.next());
  for (float& a : h) a = static_cast<float>(n.next());
  Table t(h_count, std::vector<float>(v_count));
  for (auto& row : t)
    for (float& c : row) c = static_cast<float>(factor * n.next());
  if (n.failed()) return fail("its table ends early or holds something other than numbers");
  if (!increasing(v) || !increasing(h)) return fail("its angles are not in increasing order");
  for (const auto& row : t)
    for (float c : row)
      if (!std::isfinite(c)) return fail("its candela values overflow");

  to_type_c(static_cast<int>(type), h, v, t);

  IesProfile p;
  p.edges_ = edges;
  constexpr float kRad = kPi / 180.0f;
  for (float a : h) p.h_.push_back(a * kRad);
  for (float a : v) p.v_.push_back(a * kRad);
  if (!increasing(p.h_) || !increasing(p.v_)) return fail("its angles overlap once mirrored");
  p.values_.reserve(p.h_.size() * p.v_.size());
  for (const auto& row : t) p.values_.insert(p.values_.end(), row.begin(), row.end());
  // Cycles 4.1+ interpolates across the circle or a pole only when the table reaches it by
  // these float tests, which 360 and 180 degrees, converted as above, do not pass (they round
  // to 2 pi and pi exactly): kept as Cycles has them, so the images agree.
  p.wrap_h_ = p.h_.front() < 1e-7f && p.h_.back() > 2.0f * kPi - 1e-7f;
  p.wrap_v_low_ = p.v_.front() < 1e-7f;
  p.wrap_v_high_ = p.v_.back() > kPi - 1e-7f;
  p.tabulate();
  return p;
}

IesProfile IesProfile::constant(float value) {
  IesProfile p;
  p.constant_ = std::max(value, 0.0f);
  p.tabulate();
  return p;
}

float IesProfile::vertical(int v, float v_frac, int h) const {
  const int n = static_cast<int>(v_.size());
  const float b = at(h, v), c = at(h, v + 1);
  float a, d;
  if (edges_ == IesEdges::kClamp) {
    a = at(h, v == 0 ? 1 : v - 1);  // across the pole, assuming symmetry as Cycles does
    d = at(h, std::min(v + 2, n - 1));
  } else {
    const bool zero = edges_ == IesEdges::kZero;
    a = v > 0 ? at(h, v - 1) : wrap_v_low_ ? at(h, 1) : zero ? 0.0f : b;
    d = v + 2 < n ? at(h, v + 2) : wrap_v_high_ ? at(h, n - 2) : zero ? 0.0f : c;
  }
  return catmull_rom(a, b, c, d, v_frac);
}

float IesProfile::eval_angles(float h, float v) const {
  if (constant_ >= 0.0f) return constant_;
  if (edges_ == IesEdges::kClamp) {
    // Cycles 3.x-4.0 checks only the vertical end; an angle at or past a horizontal end (h = 2
    // pi at the pole, where 3.x reads an area light) is read at that end.
    if (!(v < v_.back())) return 0.0f;
    v = std::max(v, v_.front());
    h = std::clamp(h, h_.front(), h_.back());
  } else if (!(v >= v_.front()) || !(v < v_.back()) || !(h >= h_.front()) || !(h < h_.back())) {
    return 0.0f;
  }
  // The cell [i, i + 1] with angle[i + 1] >= the angle, as Cycles' search finds it.
  const int hi = static_cast<int>(std::lower_bound(h_.begin() + 1, h_.end(), h) - h_.begin()) - 1;
  const int vi = static_cast<int>(std::lower_bound(v_.begin() + 1, v_.end(), v) - v_.begin()) - 1;
  const float hf = (h - h_[hi]) / (h_[hi + 1] - h_[hi]);
  const float vf = (v - v_[vi]) / (v_[vi + 1] - v_[vi]);
  const int hn = static_cast<int>(h_.size());
  const float b = vertical(vi, vf, hi), c = vertical(vi, vf, hi + 1);
  // Past the ends: 360 equals 0, so the entries beyond are the second and the one before last.
  const bool wrap = wrap_h_ || edges_ == IesEdges::kClamp;
  const float outside = edges_ == IesEdges::kZero ? 0.0f : b;
  const float a = hi > 0 ? vertical(vi, vf, hi - 1) : wrap ? vertical(vi, vf, hn - 2) : outside;
  const float d = hi + 2 < hn ? vertical(vi, vf, hi + 2) : wrap ? vertical(vi, vf, 1) : outside;
  return std::max(catmull_rom(a, b, c, d, hf), 0.0f);
}

float IesProfile::eval(const Vec3& local) const {
  if (constant_ >= 0.0f) return constant_;
  const float v = std::acos(std::clamp(-local.z, -1.0f, 1.0f));
  const float h = std::atan2(local.x, local.y) + kPi;
  return eval_angles(h, v);
}

void IesProfile::tabulate() {
  constexpr int kV = kVerticalCells, kH = kHorizontalCells;
  constexpr float dv = kPi / kV, dh = 2.0f * kPi / kH;
  std::vector<double> weights(size_t(kV) * kH);
  std::vector<float> solid_angle(weights.size());
  double integral = 0.0;
  float largest = 0.0f;
  for (int i = 0; i < kV; ++i) {
    const float v0 = i * dv, v1 = (i + 1) * dv;
    const float cos0 = std::cos(v0), cos1 = std::cos(v1);
    for (int j = 0; j < kH; ++j) {
      const size_t c = size_t(i) * kH + j;
      solid_angle[c] = dh * (cos0 - cos1);
      // The cell's largest value among 3 x 3 points guides sampling; 4 x 4 points uniform in
      // solid angle give its share of the integral.
      float top = 0.0f;
      for (int a = 0; a <= 2; ++a)
        for (int b = 0; b <= 2; ++b)
          top = std::max(top, eval_angles(std::min((j + 0.5f * b) * dh, 2.0f * kPi - 1e-6f),
                                          (i + 0.5f * a) * dv));
      double sum = 0.0;
      for (int a = 0; a < 4; ++a) {
        const float cv = cos0 + (cos1 - cos0) * (a + 0.5f) / 4.0f;
        for (int b = 0; b < 4; ++b) sum += eval_angles((j + (b + 0.5f) / 4.0f) * dh, std::acos(cv));
      }
      integral += sum / 16.0 * solid_angle[c];
      weights[c] = top;
      largest = std::max(largest, top);
    }
  }
  integral_ = static_cast<float>(integral);
  // A floor keeps every direction possible, so photons weighted by value / pdf stay unbiased
  // where the 3 x 3 points miss a peak.
  const double floor = largest > 0.0f ? 1e-3 * largest : 1.0;
  for (size_t c = 0; c < weights.size(); ++c) weights[c] = (weights[c] + floor) * solid_angle[c];
  cells_ = Distribution1D(weights);
  cell_pdf_.resize(weights.size());
  for (size_t c = 0; c < weights.size(); ++c) cell_pdf_[c] = cells_.probability(c) / solid_angle[c];
}

int IesProfile::cell(const Vec3& local) const {
  const float v = std::acos(std::clamp(-local.z, -1.0f, 1.0f));
  const float h = std::atan2(local.x, local.y) + kPi;
  const int i = std::clamp(static_cast<int>(v * (kVerticalCells / kPi)), 0, kVerticalCells - 1);
  const int j =
      std::clamp(static_cast<int>(h * (kHorizontalCells / (2.0f * kPi))), 0, kHorizontalCells - 1);
  return i * kHorizontalCells + j;
}

Vec3 IesProfile::sample(Vec2 u, float* pdf) const {
  float rest = 0.0f;
  const size_t c = cells_.sample(u.x, &rest);
  const int i = static_cast<int>(c / kHorizontalCells), j = static_cast<int>(c % kHorizontalCells);
  const float cos0 = std::cos(i * kPi / kVerticalCells);
  const float cos1 = std::cos((i + 1) * kPi / kVerticalCells);
  const float cos_v = cos0 + (cos1 - cos0) * rest;  // uniform in solid angle within the cell
  const float sin_v = std::sqrt(std::max(0.0f, 1.0f - cos_v * cos_v));
  const float a = (j + u.y) * (2.0f * kPi / kHorizontalCells) - kPi;  // h - pi
  *pdf = cell_pdf_[c];
  return {sin_v * std::sin(a), sin_v * std::cos(a), -cos_v};
}

float IesProfile::pdf(const Vec3& local) const {
  return cell_pdf_[cell(local)];
}

IesEmission::IesEmission(std::shared_ptr<const IesProfile> profile, float strength,
                         const Transform& light_to_world)
    : profile_(std::move(profile)), strength_(std::max(strength, 0.0f)) {
  // Cycles takes the direction into the lamp's object space; its axes, made orthonormal,
  // give the same for lamps without non-uniform scale.
  z_ = normalize(light_to_world.column(2));
  Vec3 x = light_to_world.column(0);
  x = x - z_ * dot(x, z_);
  x_ = length_squared(x) > 0.0f ? normalize(x) : Frame(z_).t;
  y_ = cross(z_, x_);
  if (dot(y_, light_to_world.column(1)) < 0.0f) y_ = -y_;
  if (!is_finite(x_) || !is_finite(y_) || !is_finite(z_)) {
    x_ = Vec3(1, 0, 0), y_ = Vec3(0, 1, 0), z_ = Vec3(0, 0, 1);
  }
}

}  // namespace photon
