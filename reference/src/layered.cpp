// CPU reference of the `layered` node: see layered.h.
#include "aquarelle/reference/layered.h"

#include <algorithm>
#include <cmath>

#include "aquarelle/reference/blur.h"
#include "aquarelle/reference/noise_reference.h"

namespace aq::reference {
namespace {

using Plane = std::vector<double>;  // one channel, row-major, row 0 at the bottom

bool is_id(double v) {
  return v >= 1.0 && v < 16777216.0 && std::floor(v) == v;
}
double finite_or(double v, double fallback) {
  return std::isfinite(v) ? v : fallback;
}

Plane blur(const Plane& in, int w, int h, double sigma) {
  const std::vector<double> k = gaussian_kernel(sigma, 4.0);
  const int r = static_cast<int>(k.size()) - 1;
  Plane tmp(in.size()), out(in.size());
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      double s = 0.0;
      for (int i = -r; i <= r; ++i) s += k[std::abs(i)] * in[y * w + std::clamp(x + i, 0, w - 1)];
      tmp[y * w + x] = s;
    }
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      double s = 0.0;
      for (int i = -r; i <= r; ++i) s += k[std::abs(i)] * tmp[std::clamp(y + i, 0, h - 1) * w + x];
      out[y * w + x] = s;
    }
  return out;
}

// The maximum over a (2r+1)^2 window, clamped to the image.
Plane running_max(const Plane& in, int w, int h, int r) {
  Plane tmp(in.size()), out(in.size());
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      double m = in[y * w + x];
      for (int i = -r; i <= r; ++i) m = std::max(m, in[y * w + std::clamp(x + i, 0, w - 1)]);
      tmp[y * w + x] = m;
    }
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      double m = tmp[y * w + x];
      for (int i = -r; i <= r; ++i) m = std::max(m, tmp[std::clamp(y + i, 0, h - 1) * w + x]);
      out[y * w + x] = m;
    }
  return out;
}

double smoothstep(double e0, double e1, double x) {
  const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

std::array<double, 3> normalised(std::array<double, 3> v, std::array<double, 3> fallback) {
  const double len = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  if (!(len > 1e-12) || !std::isfinite(len)) return fallback;
  return {v[0] / len, v[1] / len, v[2] / len};
}

Rgb glaze(const Rgb& under, const Rgb& colour, double thickness, MixMode mode) {
  if (mode == MixMode::kKubelkaMunk) return km_glaze(under, colour, thickness);
  Rgb c = sanitize(colour);
  for (double& v : c) v = std::pow(v, std::max(thickness, 1.0));
  return mix(under, c, std::min(thickness, 1.0), mode);
}

// The soft shadow layer (README "Soft shadows"): the binary shadow times a smooth step over
// the gap behind the occluder, blurred over the receivers (a normalised convolution), glazed
// over the painting on the receivers.
void glaze_shadow(const ImageF& id, const ImageF& shadow, const LayeredParams& p,
                  std::vector<Rgb>& under) {
  const int w = id.width, h = id.height;
  const size_t n = static_cast<size_t>(w) * h;
  Plane shadowed(n, 0.0), receiver(n, 0.0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (!is_id(id.at(x, y, 0))) continue;
      const size_t i = static_cast<size_t>(y) * w + x;
      receiver[i] = 1.0;
      if (shadow.at(x, y, 0) < 0.5) {
        shadowed[i] = smoothstep(0.0, std::max(p.shadow_band, 1e-6), shadow.at(x, y, 1));
      }
    }
  const Plane s = blur(shadowed, w, h, p.shadow_softness);
  const Plane r = blur(receiver, w, h, p.shadow_softness);
  for (size_t i = 0; i < n; ++i) {
    if (receiver[i] < 0.5) continue;
    const double amount = r[i] > 1e-6 ? std::clamp(s[i] / r[i], 0.0, 1.0) : 0.0;
    under[i] = glaze(under[i], p.shadow_color, p.shadows * amount, p.mixing);
  }
}

}  // namespace

std::vector<LayeredObject> layered_objects(const ImageF& id, const ImageF& depth,
                                           const ImageF& albedo) {
  struct Sum {
    double pixels = 0, depth_pixels = 0, depth = 0;
    Rgb albedo{};
  };
  std::map<float, Sum> sums;
  for (int y = 0; y < id.height; ++y)
    for (int x = 0; x < id.width; ++x) {
      const float v = id.at(x, y, 0);
      if (!is_id(v)) continue;
      Sum& s = sums[v];
      s.pixels += 1;
      const double z = depth.at(x, y, 0);
      if (z > 0.0 && z < 3.0e38) {
        s.depth += z;
        s.depth_pixels += 1;
      }
      for (int c = 0; c < 3; ++c) {
        const double a = albedo.at(x, y, c);
        s.albedo[c] += a >= 0.0 ? std::min(a, 1.0) : 0.0;
      }
    }
  std::vector<LayeredObject> objects;
  for (const auto& [v, s] : sums) {
    LayeredObject o;
    o.id = v;
    o.mean_depth = s.depth_pixels > 0 ? s.depth / s.depth_pixels : 0.0;
    for (int c = 0; c < 3; ++c) o.mean_albedo[c] = s.albedo[c] / s.pixels;
    objects.push_back(o);
  }
  std::stable_sort(objects.begin(), objects.end(), [](const auto& a, const auto& b) {
    return a.mean_depth != b.mean_depth ? a.mean_depth > b.mean_depth : a.id < b.id;
  });
  return objects;
}

ImageF layered(const ImageF& id, const ImageF& normal, const ImageF& albedo, const ImageF& depth,
               const ImageF* paper, const LayeredParams& p, const ImageF* shadow) {
  const int w = id.width, h = id.height;
  const size_t n = static_cast<size_t>(w) * h;
  const auto light = normalised(
      {-p.light_direction[0], -p.light_direction[1], -p.light_direction[2]}, {0.0, 1.0, 0.0});
  const auto view = normalised(p.view_direction, {0.0, 0.0, 1.0});
  const auto half = normalised({light[0] + view[0], light[1] + view[1], light[2] + view[2]}, light);

  // Per pixel: diffuse, highlight, depth, paper height, abstraction threshold.
  Plane diffuse(n), highlight(n), z(n), paper_h(n, 0.5), t(n);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t i = static_cast<size_t>(y) * w + x;
      std::array<double, 3> nv{normal.at(x, y, 0), normal.at(x, y, 1), normal.at(x, y, 2)};
      const double len = std::sqrt(nv[0] * nv[0] + nv[1] * nv[1] + nv[2] * nv[2]);
      if (len > 1e-6 && len < 1e30) {
        for (double& c : nv) c /= len;
      } else {
        nv = {0.0, 0.0, 0.0};
      }
      const double nl = nv[0] * light[0] + nv[1] * light[1] + nv[2] * light[2];
      const double nh = nv[0] * half[0] + nv[1] * half[1] + nv[2] * half[2];
      diffuse[i] = std::clamp(nl, 0.0, 1.0);
      highlight[i] = std::pow(std::max(nh, 0.0), p.shininess) >= p.specular_threshold ? 1.0 : 0.0;
      const double zv = depth.at(x, y, 0);
      z[i] = zv > 0.0 && zv < 3.0e38 ? zv : 0.0;
      if (paper != nullptr) {
        const double hv = paper->at(x, y, 0);
        paper_h[i] = hv >= 0.0 ? std::min(hv, 1.0) : 0.5;
      }
      t[i] = p.threshold;
      if (p.edge_noise > 0.0) {
        t[i] += p.edge_noise *
                noise::fbm2({(x + 0.5) / p.noise_scale, (y + 0.5) / p.noise_scale}, {0.0, 0.0}, 3);
      }
    }

  // The paper.
  std::vector<Rgb> under(n);
  for (size_t i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c)
      under[i][c] = p.paper_color[c] * (1.0 + p.paper_relief * (paper_h[i] - 0.5));

  const double s = std::max(p.softness, 1e-4);
  const bool edges_on = p.wet_edges != 2 || !p.wet_in_wet_ids.empty();
  const double gain = edges_on ? std::max(1.0, 1.2533 * p.edge_width) : 0.0;
  const double th = std::max(p.edge_threshold, 1e-6);
  const double granulation_weight = paper != nullptr ? p.granulation : 0.0;

  for (const LayeredObject& object : layered_objects(id, depth, albedo)) {
    Rgb light_colour{}, dark_colour{};
    const auto palette = p.palette_light.find(object.id);
    for (int c = 0; c < 3; ++c) {
      if (palette != p.palette_light.end()) {
        light_colour[c] = palette->second[c];
        dark_colour[c] = std::pow(palette->second[c], p.dark_density / p.light_density);
      } else {
        light_colour[c] = std::pow(object.mean_albedo[c], p.light_density);
        dark_colour[c] = std::pow(object.mean_albedo[c], p.dark_density);
      }
    }
    light_colour = mix(light_colour, p.warm, p.gooch, p.mixing);
    dark_colour = mix(dark_colour, p.cool, p.gooch, p.mixing);
    const bool wet_in_wet =
        p.wet_edges == 1 || std::find(p.wet_in_wet_ids.begin(), p.wet_in_wet_ids.end(),
                                      object.id) != p.wet_in_wet_ids.end();

    // Segmentation and lighting (premultiplied by the intensity).
    Plane intensity(n), lit(n), layer_depth(n);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const size_t i = static_cast<size_t>(y) * w + x;
        const double mask = id.at(x, y, 0) == object.id ? 1.0 : 0.0;
        intensity[i] = mask * (1.0 - highlight[i]);
        lit[i] = intensity[i] * diffuse[i];
        layer_depth[i] = intensity[i] * z[i];
      }
    const Plane b = blur(intensity, w, h, p.abstraction_sigma);
    const Plane bd = blur(lit, w, h, p.abstraction_sigma);
    const Plane bz = blur(layer_depth, w, h, p.abstraction_sigma);
    const bool thin = p.thin_shapes > 0.0 && p.abstraction_sigma > 0.0;
    const Plane peak =
        thin ? running_max(b, w, h, static_cast<int>(std::ceil(p.abstraction_sigma)) + 1) : b;
    const double line_width_scale = std::sqrt(2.0 * 3.14159265358979) * p.abstraction_sigma;

    // Wet edges.
    Plane edges(n, 0.0);
    if (edges_on) {
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
          const size_t i = static_cast<size_t>(y) * w + x;
          auto a_at = [&](int xx, int yy) {
            const size_t j =
                static_cast<size_t>(std::clamp(yy, 0, h - 1)) * w + std::clamp(xx, 0, w - 1);
            return smoothstep(t[i] - s, t[i] + s, b[j]);  // the centre's threshold
          };
          double sum = 0.0;
          for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx)
              if (dx != 0 || dy != 0) sum += a_at(x + dx, y + dy);
          edges[i] = smoothstep(th, 2.0 * th, std::abs(sum - 8.0 * a_at(x, y)));
        }
      edges = blur(edges, w, h, p.edge_width);
    }

    // Glaze.
    for (size_t i = 0; i < n; ++i) {
      if (!(b[i] > 1e-6)) continue;
      double a = smoothstep(t[i] - s, t[i] + s, b[i]);
      if (thin) {
        const double ridge = smoothstep(0.75, 0.9, b[i] / std::max(peak[i], 1e-6));
        const double wide_enough = smoothstep(0.5, 1.0, peak[i] * line_width_scale);
        a = std::max(a, p.thin_shapes * intensity[i] * ridge * wide_enough);
      }
      const double d = std::clamp(bd[i] / b[i], 0.0, 1.0);
      const Rgb colour = mix(dark_colour, light_colour, d, p.mixing);
      const double e = std::clamp(gain * edges[i], 0.0, 1.0);
      const double wet = 1.0 - (1.0 - e) * (1.0 - e);
      double cover = a, extra = 0.0;
      if (wet_in_wet) {
        cover = std::max(a, p.wet_spread * wet);
      } else {
        extra = p.edge_darkness * wet * a;
      }
      extra +=
          p.edge_darkening * std::clamp((1.0 - b[i]) / std::max(1.0 - t[i], 1e-3), 0.0, 1.0) * a;
      const double front = z[i];
      const double visible =
          front > 0.0 ? 1.0 - smoothstep(0.0, std::max(p.depth_band, 1e-6), bz[i] / b[i] - front)
                      : 1.0;
      const double granulation = 1.0 + (2.0 * (1.0 - paper_h[i]) - 1.0) * granulation_weight;
      const double thickness = p.density * cover * visible * granulation * (1.0 + extra);
      under[i] = glaze(under[i], colour, thickness, p.mixing);
    }
  }

  if (shadow != nullptr) glaze_shadow(id, *shadow, p, under);

  ImageF out(w, h, 4, 1.0f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c)
        out.at(x, y, c) =
            static_cast<float>(finite_or(under[static_cast<size_t>(y) * w + x][c], 0.0));
  return out;
}

}  // namespace aq::reference
