// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{A hexahedral mesh of the bellows}
//
// See include/core/bellows_mesh.h.

#include <algorithm>
#include <cmath>
#include <core/bellows_mesh.h>
#include <deal.II/base/exceptions.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/manifold_lib.h>
#include <fstream>
#include <regex>
#include <set>

namespace SoftRobot
{
  // @sect4{BellowsDesign::read}
  //
  // Only the lines that assign a plain number are read; derived quantities
  // (`SmallRounding = FoldRadius - WallThickness / 2;`) are computed again
  // below, as bellows.geo computes them.
  BellowsDesign
  BellowsDesign::read(const std::string &geo_file)
  {
    std::ifstream file(geo_file);
    AssertThrow(file,
                ExcMessage("Cannot open the bellows design file '" + geo_file +
                           "' (Geometry/Mesh file with Mesh source = "
                           "bellows)."));
    static const std::regex assignment(
      R"(^\s*([A-Za-z]\w*)\s*=\s*([-+]?[0-9]*\.?[0-9]+([eE][-+]?[0-9]+)?)\s*;)");
    std::map<std::string, double> numbers;
    std::string                   line;
    while (std::getline(file, line))
      {
        std::smatch match;
        if (std::regex_search(line, match, assignment))
          numbers[match[1].str()] = std::stod(match[2].str());
      }

    const auto get =
      [&](const std::string &name, const double lower, const double upper) {
        const auto entry = numbers.find(name);
        AssertThrow(entry != numbers.end(),
                    ExcMessage("The bellows design file '" + geo_file +
                               "' has no line '" + name + " = <number>;'."));
        AssertThrow(entry->second > lower && entry->second < upper,
                    ExcMessage("The bellows design file '" + geo_file + "': " +
                               name + " = " + std::to_string(entry->second) +
                               " is outside the allowed range (" +
                               std::to_string(lower) + ", " +
                               std::to_string(upper) + ")."));
        return entry->second;
      };
    const auto count = [&](const std::string &name, const double upper) {
      const double value = get(name, 0.5, upper);
      AssertThrow(value == std::round(value),
                  ExcMessage("The bellows design file '" + geo_file +
                             "': " + name + " = " + std::to_string(value) +
                             " must be a whole number."));
      return static_cast<unsigned int>(value);
    };

    BellowsDesign design;
    design.x_base               = get("XBase", -1e6, 1e6);
    design.end_wall             = get("EndWall", 0, 1e6);
    design.inlet_radius         = get("InletRadius", 0, 1e6);
    design.ring_radius          = get("RingRadius", 0, 1e6);
    design.neck_radius          = get("NeckRadius", 0, 1e6);
    design.neck_length          = get("NeckLength", 0, 1e6);
    design.n_convolutions       = count("NumConvolutions", 1000);
    design.pitch                = get("Pitch", 0, 1e6);
    design.inner_crest_radius   = get("InnerCrestRadius", 0, 1e6);
    design.wall_thickness       = get("WallThickness", 0, 1e6);
    design.fold_radius          = get("FoldRadius", 0, 1e6);
    design.chords_cavity_valley = count("ChordsCavityValley", 64);
    design.chords_cavity_crest  = count("ChordsCavityCrest", 64);
    design.chords_outer_crest   = count("ChordsOuterCrest", 64);
    design.chords_outer_valley  = count("ChordsOuterValley", 64);
    design.block_length         = get("BlockLength", 0, 1e6);
    design.block_width          = get("BlockWidth", 0, 1e6);

    // What the structured mesh needs beyond what bellows.geo checks: the
    // stations of a fold end on its smaller side at the vertices of that
    // side's chords, and the half valleys at both ends keep a vertex at
    // their bottom.
    AssertThrow(design.chords_cavity_valley % 2 == 0,
                ExcMessage("The bellows design file '" + geo_file +
                           "': ChordsCavityValley must be even."));
    AssertThrow(design.chords_cavity_valley % design.chords_outer_valley == 0 &&
                  design.chords_outer_crest % design.chords_cavity_crest == 0,
                ExcMessage(
                  "The bellows design file '" + geo_file +
                  "': the hexahedral mesh needs ChordsOuterValley to divide "
                  "ChordsCavityValley and ChordsCavityCrest to divide "
                  "ChordsOuterCrest."));
    AssertThrow(design.block_radius() > design.ring_radius,
                ExcMessage("The bellows design file '" + geo_file +
                           "': the cylindrical tip block (radius BlockWidth / "
                           "sqrt(3)) must cover the cap's end disc of radius "
                           "RingRadius."));
    return design;
  }



  double
  BellowsDesign::block_radius() const
  {
    return block_width / std::sqrt(3.);
  }



  double
  BellowsDesign::x_end() const
  {
    return x_base + 2. * end_wall + n_convolutions * pitch;
  }



  // @sect4{The section's areas and volumes}
  namespace
  {
    // The signed area of a quadrilateral in deal.II's vertex order, whose
    // boundary runs 0, 1, 3, 2.
    double
    signed_area(const BellowsSection &section, const unsigned int q)
    {
      const std::array<unsigned int, 4> &v = section.quads[q];
      const std::array<unsigned int, 4>  loop{{v[0], v[1], v[3], v[2]}};
      double                             area = 0.;
      for (unsigned int i = 0; i < 4; ++i)
        {
          const Point<2> &a = section.vertices[loop[i]];
          const Point<2> &b = section.vertices[loop[(i + 1) % 4]];
          area += 0.5 * (a[0] * b[1] - b[0] * a[1]);
        }
      return area;
    }

    // The centroid's radius of the same quadrilateral, from its two
    // triangles.
    double
    centroid_radius(const BellowsSection &section, const unsigned int q)
    {
      const std::array<unsigned int, 4> &v      = section.quads[q];
      double                             moment = 0., area = 0.;
      for (const std::array<unsigned int, 3> triangle :
           {std::array<unsigned int, 3>{{v[0], v[1], v[3]}},
            std::array<unsigned int, 3>{{v[0], v[3], v[2]}}})
        {
          const Point<2> &a = section.vertices[triangle[0]];
          const Point<2> &b = section.vertices[triangle[1]];
          const Point<2> &c = section.vertices[triangle[2]];
          const double    triangle_area =
            0.5 * std::abs((b[0] - a[0]) * (c[1] - a[1]) -
                           (c[0] - a[0]) * (b[1] - a[1]));
          moment += triangle_area * (a[1] + b[1] + c[1]) / 3.;
          area += triangle_area;
        }
      return moment / area;
    }
  } // namespace

  double
  BellowsSection::area(const types::material_id material) const
  {
    double result = 0.;
    for (unsigned int q = 0; q < quads.size(); ++q)
      if (materials[q] == material)
        result += std::abs(signed_area(*this, q));
    return result;
  }

  double
  BellowsSection::revolved_volume(const types::material_id material) const
  {
    double result = 0.;
    for (unsigned int q = 0; q < quads.size(); ++q)
      if (materials[q] == material)
        result += 2. * numbers::PI * std::abs(signed_area(*this, q)) *
                  centroid_radius(*this, q);
    return result;
  }



  // @sect4{Building the section}
  //
  // The section is built patch by patch. A patch is a grid of points,
  // `rows[k][i]` with i along the wall (or the block) and k across it, and
  // its quadrilaterals join neighbouring points; vertices that two patches
  // share are found by their coordinates.
  namespace
  {
    class SectionBuilder
    {
    public:
      explicit SectionBuilder(const double length_scale)
        : tolerance(1e-9 * length_scale)
      {
      }

      unsigned int
      vertex(const Point<2> &p)
      {
        for (unsigned int i = 0; i < section.vertices.size(); ++i)
          if (section.vertices[i].distance(p) < tolerance)
            return i;
        section.vertices.push_back(p);
        return section.vertices.size() - 1;
      }

      void
      add_grid(const std::vector<std::vector<Point<2>>> &rows,
               const types::material_id                  material,
               const bool                                on_axis = false)
      {
        for (unsigned int k = 0; k + 1 < rows.size(); ++k)
          for (unsigned int i = 0; i + 1 < rows[k].size(); ++i)
            {
              section.quads.push_back({{vertex(rows[k][i]),
                                        vertex(rows[k][i + 1]),
                                        vertex(rows[k + 1][i]),
                                        vertex(rows[k + 1][i + 1])}});
              section.materials.push_back(material);
              section.on_axis.push_back(on_axis);
            }
      }

      // The ruled patch between two polylines with as many points, at the
      // given fractions (0 on the first polyline, 1 on the second).
      void
      add_ruled(const std::vector<Point<2>> &first,
                const std::vector<Point<2>> &second,
                const std::vector<double>   &fractions,
                const types::material_id     material)
      {
        Assert(first.size() == second.size(), ExcInternalError());
        std::vector<std::vector<Point<2>>> rows;
        for (const double s : fractions)
          {
            std::vector<Point<2>> row;
            for (unsigned int i = 0; i < first.size(); ++i)
              row.push_back(first[i] + s * (second[i] - first[i]));
            rows.push_back(row);
          }
        add_grid(rows, material);
      }

      // The patch of a rectangle (in x and r) given by its grid lines.
      void
      add_rectangle(const std::vector<double> &x_levels,
                    const std::vector<double> &r_levels,
                    const types::material_id   material,
                    const bool                 on_axis = false)
      {
        std::vector<std::vector<Point<2>>> rows;
        for (const double r : r_levels)
          {
            std::vector<Point<2>> row;
            for (const double x : x_levels)
              row.emplace_back(x, r);
            rows.push_back(row);
          }
        add_grid(rows, material, on_axis);
      }

      BellowsSection section;

    private:
      const double tolerance;
    };

    // n + 1 evenly spaced values from a to b.
    std::vector<double>
    linspace(const double a, const double b, const unsigned int n)
    {
      std::vector<double> values;
      for (unsigned int i = 0; i <= n; ++i)
        values.push_back(a + (b - a) * i / n);
      return values;
    }

    Tensor<1, 2>
    unit(const double angle)
    {
      return Tensor<1, 2>({std::cos(angle), std::sin(angle)});
    }

    // The point at the fraction s of a polyline whose n chords are equally
    // long: the polygon's side of a fold with the smaller radius.
    Point<2>
    along_chords(const Point<2>    &centre,
                 const double       radius,
                 const double       first_angle,
                 const double       last_angle,
                 const unsigned int n_chords,
                 const double       s)
    {
      const double       position = s * n_chords;
      const unsigned int chord =
        std::min<unsigned int>(n_chords - 1,
                               static_cast<unsigned int>(position + 1e-12));
      const double   local = position - chord;
      const double   step  = (last_angle - first_angle) / n_chords;
      const Point<2> a     = centre + radius * unit(first_angle + chord * step);
      const Point<2> b =
        centre + radius * unit(first_angle + (chord + 1) * step);
      return a + local * (b - a);
    }

    // A segment across the wall: its point on the cavity side and on the
    // outer side.
    struct Station
    {
      Point<2> inner, outer;
    };
  } // namespace



  BellowsSection
  make_bellows_section(const BellowsDesign     &d,
                       const BellowsResolution &resolution)
  {
    const unsigned int n_t = resolution.cells_through_wall;
    const unsigned int n_f = resolution.cells_along_flank;
    const unsigned int n_c = resolution.cells_per_chord;
    AssertThrow(n_t >= 1 && n_f >= 1 && n_c >= 1, ExcInternalError());

    // The derived quantities of bellows.geo: the two radii of the sides of a
    // fold, the radii of the folds' centres, and the unit normal
    // $(\cos\beta, \sin\beta)$ of the flanks.
    const double small           = d.fold_radius - d.wall_thickness / 2.;
    const double large           = d.fold_radius + d.wall_thickness / 2.;
    const double crest_centre_r  = d.inner_crest_radius - small;
    const double valley_centre_r = d.inlet_radius + large;
    const double half_pitch      = d.pitch / 2.;
    const double x_first_valley  = d.x_base + d.end_wall;
    const double x_last_valley   = x_first_valley + d.n_convolutions * d.pitch;
    const double x_end           = d.x_end();
    const double centre_distance =
      std::hypot(half_pitch, crest_centre_r - valley_centre_r);
    AssertThrow(small > 0. && 2. * d.fold_radius < centre_distance,
                ExcMessage("The bellows design: FoldRadius and WallThickness "
                           "leave no straight flank."));
    const double ux   = half_pitch / centre_distance;
    const double ur   = -(crest_centre_r - valley_centre_r) / centre_distance;
    const double sinb = 2. * d.fold_radius / centre_distance;
    const double cosb = std::sqrt(1. - sinb * sinb);
    const double beta =
      std::atan2(sinb * ur + cosb * ux, sinb * ux - cosb * ur);
    const double pi = numbers::PI;

    // The neck: where the first outer flank rises through NeckRadius.
    const Point<2> flank_low(x_first_valley + small * std::cos(beta),
                             valley_centre_r - small * std::sin(beta));
    const Point<2> flank_high(x_first_valley + half_pitch -
                                large * std::cos(beta),
                              crest_centre_r + large * std::sin(beta));
    AssertThrow(d.neck_radius > flank_low[1] && d.neck_radius < flank_high[1],
                ExcMessage("The bellows design: NeckRadius must lie on the "
                           "straight outer flank."));
    const double x_neck = flank_low[0] + (d.neck_radius - flank_low[1]) *
                                           (flank_high[0] - flank_low[0]) /
                                           (flank_high[1] - flank_low[1]);
    AssertThrow(x_neck - d.neck_length > d.x_base &&
                  x_neck - d.neck_length < x_first_valley &&
                  x_first_valley < x_neck,
                ExcMessage("The bellows design: the neck must span the bottom "
                           "of the first cavity valley."));

    // <em>The stations of the wall.</em>
    //
    // Along the wall from the bottom of the first cavity valley to the
    // bottom of the last. A valley's larger side is the cavity's, a crest's
    // the outer one.
    // Stations per fold: the chords of the side with the larger radius,
    // each divided into `Cells per chord`.
    const unsigned int cv = d.chords_cavity_valley * n_c;
    const unsigned int cc = d.chords_outer_crest * n_c;
    const auto valley     = [&](const unsigned int k, const unsigned int j) {
      const Point<2> centre(x_first_valley + k * d.pitch, valley_centre_r);
      const double   first = pi + beta, last = 2. * pi - beta;
      return Station{
        along_chords(
          centre, large, first, last, d.chords_cavity_valley, double(j) / cv),
        along_chords(
          centre, small, first, last, d.chords_outer_valley, double(j) / cv)};
    };
    const auto crest = [&](const unsigned int k, const unsigned int j) {
      const Point<2> centre(x_first_valley + k * d.pitch + half_pitch,
                            crest_centre_r);
      const double   first = pi - beta, last = beta;
      return Station{
        along_chords(
          centre, small, first, last, d.chords_cavity_crest, double(j) / cc),
        along_chords(
          centre, large, first, last, d.chords_outer_crest, double(j) / cc)};
    };

    std::vector<Station> stations;
    const auto flank_to = [&](const Station &end, const unsigned int n) {
      const Station start = stations.back();
      for (unsigned int i = 1; i <= n; ++i)
        stations.push_back(
          {start.inner + (double(i) / n) * (end.inner - start.inner),
           start.outer + (double(i) / n) * (end.outer - start.outer)});
    };
    // The station through the neck's corner on the first rising flank, and
    // its mirror image on the last descending one.
    const Point<2> neck_corner(x_neck, d.neck_radius);
    const Station  first_neck{neck_corner + d.wall_thickness *
                                             Tensor<1, 2>({std::cos(beta),
                                                            -std::sin(beta)}),
                             neck_corner};
    const auto     mirror = [&](const Point<2> &p) {
      return Point<2>(d.x_base + x_end - p[0], p[1]);
    };
    const Station last_neck{mirror(first_neck.inner), mirror(first_neck.outer)};

    for (unsigned int j = cv / 2; j <= cv; ++j)
      stations.push_back(valley(0, j));
    stations.push_back(first_neck);
    for (unsigned int k = 0; k < d.n_convolutions; ++k)
      {
        flank_to(crest(k, 0), n_f);
        for (unsigned int j = 1; j <= cc; ++j)
          stations.push_back(crest(k, j));
        if (k + 1 < d.n_convolutions)
          {
            flank_to(valley(k + 1, 0), n_f);
            for (unsigned int j = 1; j <= cv; ++j)
              stations.push_back(valley(k + 1, j));
          }
      }
    flank_to(last_neck, n_f);
    for (unsigned int j = 0; j <= cv / 2; ++j)
      stations.push_back(valley(d.n_convolutions, j));

    SectionBuilder builder(x_end - d.x_base);
    {
      std::vector<Point<2>> inner, outer;
      for (const Station &s : stations)
        {
          inner.push_back(s.inner);
          outer.push_back(s.outer);
        }
      builder.add_ruled(inner, outer, linspace(0., 1., n_t), 1);
    }

    // <em>The base ring and the end cap.</em>
    //
    // At the base: the patch between the outer side of the half valley,
    // the flank up to the neck's corner and the neck (one cell across); the
    // neck column below the neck; and the ring. Their horizontal grid lines
    // continue those of the wall's first station. The cap is their mirror
    // image, with the core about the axis below it.
    const Station       bottom       = valley(0, cv / 2);
    const double        x_neck_start = x_neck - d.neck_length;
    std::vector<double> r_levels =
      linspace(d.inlet_radius, bottom.outer[1], n_t);
    r_levels.push_back(d.neck_radius);
    {
      const std::vector<double> upper =
        linspace(d.neck_radius, d.ring_radius, 2 * n_t);
      r_levels.insert(r_levels.end(), upper.begin() + 1, upper.end());
    }
    const unsigned int        n_neck_rows = n_t + 1;
    const std::vector<double> ring_x_levels =
      linspace(d.x_base, x_neck_start, n_t + 1);

    for (const bool at_end : {false, true})
      {
        const auto place = [&](const Point<2> &p) {
          return at_end ? mirror(p) : p;
        };
        std::vector<Point<2>> cover_bottom, cover_top;
        for (unsigned int j = 0; j <= cv / 2; ++j)
          cover_bottom.push_back(place(stations[j].outer));
        for (const double x : linspace(x_first_valley, x_neck, cv / 2))
          cover_top.push_back(place(Point<2>(x, d.neck_radius)));
        builder.add_ruled(cover_bottom, cover_top, {0., 1.}, 1);

        std::vector<std::vector<Point<2>>> neck, ring;
        for (unsigned int k = 0; k <= n_neck_rows; ++k)
          neck.push_back({place(Point<2>(x_neck_start, r_levels[k])),
                          place(Point<2>(x_first_valley, r_levels[k]))});
        builder.add_grid(neck, 1);
        for (const double r : r_levels)
          {
            std::vector<Point<2>> row;
            for (const double x : ring_x_levels)
              row.push_back(place(Point<2>(x, r)));
            ring.push_back(row);
          }
        builder.add_grid(ring, 1);
      }

    // The core of the cap, from the axis to the inlet radius, below the
    // mirrored neck column and ring; then the block, whose rows continue
    // those of the ring, and one more to the block's radius.
    std::vector<double> core_x_levels{x_last_valley};
    for (auto x = ring_x_levels.rbegin(); x != ring_x_levels.rend(); ++x)
      core_x_levels.push_back(d.x_base + x_end - *x);
    builder.add_rectangle(core_x_levels, {0., d.inlet_radius}, 1, true);

    const std::vector<double> block_x_levels =
      linspace(x_end, x_end + d.block_length, n_t);
    builder.add_rectangle(block_x_levels, {0., d.inlet_radius}, 2, true);
    std::vector<double> block_r_levels = r_levels;
    block_r_levels.push_back(d.block_radius());
    builder.add_rectangle(block_x_levels, block_r_levels, 2);

    // <em>Boundary edges.</em>
    //
    // An edge of one quadrilateral only is on the boundary. Its id follows
    // from where it lies: on the base face, on the block, on the cavity
    // (whose polyline is the inner side of the wall's stations, the inlet
    // channel and the disc closing the cavity), or on the rest of the
    // silicone's surface; edges on the axis get none.
    BellowsSection &section = builder.section;
    section.core_radius     = d.inlet_radius;
    std::map<std::pair<unsigned int, unsigned int>,
             std::pair<unsigned int, unsigned int>>
      edge_use; // edge -> (count, quad)
    for (unsigned int q = 0; q < section.quads.size(); ++q)
      {
        const std::array<unsigned int, 4> &v = section.quads[q];
        for (const auto &[a, b] : {std::make_pair(v[0], v[1]),
                                   std::make_pair(v[1], v[3]),
                                   std::make_pair(v[3], v[2]),
                                   std::make_pair(v[2], v[0])})
          {
            auto &use = edge_use[std::minmax(a, b)];
            use.first += 1;
            use.second = q;
          }
      }
    std::vector<std::pair<Point<2>, Point<2>>> cavity;
    cavity.emplace_back(Point<2>(d.x_base, d.inlet_radius),
                        Point<2>(x_first_valley, d.inlet_radius));
    for (unsigned int i = 0; i + 1 < stations.size(); ++i)
      cavity.emplace_back(stations[i].inner, stations[i + 1].inner);
    cavity.emplace_back(Point<2>(x_last_valley, d.inlet_radius),
                        Point<2>(x_last_valley, 0.));
    const double tolerance  = 1e-9 * (x_end - d.x_base);
    const auto   on_segment = [&](const Point<2>                      &p,
                                const std::pair<Point<2>, Point<2>> &s) {
      const Tensor<1, 2> along = s.second - s.first;
      const double       t = ((p - s.first) * along) / along.norm_square();
      return t > -1e-9 && t < 1. + 1e-9 &&
             (s.first + t * along).distance(p) < tolerance;
    };
    for (const auto &[edge, use] : edge_use)
      {
        if (use.first != 1)
          continue;
        const Point<2> &a = section.vertices[edge.first];
        const Point<2> &b = section.vertices[edge.second];
        if (std::abs(a[1]) < tolerance && std::abs(b[1]) < tolerance)
          continue;
        types::boundary_id id = 6;
        if (section.materials[use.second] == 2)
          id = 5;
        else if (std::abs(a[0] - d.x_base) < tolerance &&
                 std::abs(b[0] - d.x_base) < tolerance)
          id = 1;
        else
          for (const auto &segment : cavity)
            if (on_segment(a, segment) && on_segment(b, segment))
              id = 2;
        section.boundary_edges[edge] = id;
      }
    return section;
  }



  // @sect4{make_bellows_mesh}
  //
  // The vertices of the revolved cells are the section's vertices off the
  // axis at each angle of the turn (the last angle of a full turn is the
  // first); the cores add a square grid of points at each of their x
  // levels. For the boundary ids the origin of every vertex is kept: a
  // revolved face is either on a symmetry plane (all its vertices at the
  // first or the last angle) or swept by a boundary edge of the section.
  void
  make_bellows_mesh(const BellowsDesign     &design,
                    const BellowsResolution &resolution,
                    const unsigned int       quarters,
                    Triangulation<3>        &triangulation)
  {
    AssertThrow(quarters == 1 || quarters == 2 || quarters == 4,
                ExcInternalError());
    AssertThrow(resolution.cells_per_quarter_turn >= 2 &&
                  resolution.cells_per_quarter_turn % 2 == 0,
                ExcInternalError());
    const BellowsSection section = make_bellows_section(design, resolution);
    const unsigned int   n_phi   = resolution.cells_per_quarter_turn * quarters;
    const bool           full    = (quarters == 4);
    const unsigned int   n_angles  = full ? n_phi : n_phi + 1;
    const double         tolerance = 1e-9 * (design.x_end() - design.x_base);

    std::vector<Point<3>> vertices;
    // revolved[v][j]: the vertex of section vertex v at angle j
    std::vector<std::vector<unsigned int>> revolved(section.vertices.size());
    std::vector<std::pair<int, int>>       origin; // (section vertex, angle)
    for (unsigned int v = 0; v < section.vertices.size(); ++v)
      {
        const Point<2> &p = section.vertices[v];
        if (p[1] < tolerance)
          continue;
        for (unsigned int j = 0; j < n_angles; ++j)
          {
            const double phi = 0.5 * numbers::PI * quarters * j / n_phi;
            revolved[v].push_back(vertices.size());
            vertices.emplace_back(p[0],
                                  p[1] * std::cos(phi),
                                  p[1] * std::sin(phi));
            origin.emplace_back(v, j);
          }
      }
    const auto at_angle = [&](const unsigned int v, const unsigned int j) {
      return revolved[v][j % n_angles];
    };

    std::vector<CellData<3>> cells;
    std::vector<bool>        cell_revolved;
    const auto add_cell = [&](const std::array<unsigned int, 8> &corners,
                              const types::material_id           material,
                              const bool                         is_revolved) {
      CellData<3> cell;
      for (unsigned int i = 0; i < 8; ++i)
        cell.vertices[i] = corners[i];
      cell.material_id = material;
      cells.push_back(cell);
      cell_revolved.push_back(is_revolved);
    };

    for (unsigned int q = 0; q < section.quads.size(); ++q)
      {
        if (section.on_axis[q])
          continue;
        const std::array<unsigned int, 4> &v = section.quads[q];
        for (unsigned int j = 0; j < n_phi; ++j)
          add_cell({{at_angle(v[0], j),
                     at_angle(v[1], j),
                     at_angle(v[2], j),
                     at_angle(v[3], j),
                     at_angle(v[0], j + 1),
                     at_angle(v[1], j + 1),
                     at_angle(v[2], j + 1),
                     at_angle(v[3], j + 1)}},
                   section.materials[q],
                   true);
      }

    // <em>The cores.</em>
    //
    // The core's square has the half width a = r_c / 2 and m = (cells per
    // quarter turn) / 2 cells per half side; its grid spans [0, a] (quarter
    // model) or [-a, a] (half and full) in y, and [0, a] or [-a, a] in z.
    // The ring of cells about it joins the square's outer boundary, walked
    // in the sense of increasing angle from the point (a, 0), to the circle
    // of the revolved cells.
    const unsigned int               m  = resolution.cells_per_quarter_turn / 2;
    const double                     rc = section.core_radius;
    const double                     a  = 0.5 * rc;
    const int                        i_low = (quarters == 1) ? 0 : -int(m);
    const int                        k_low = (quarters == 4) ? -int(m) : 0;
    std::vector<std::pair<int, int>> path; // (i, k) with y = a i/m, z = a k/m
    {
      const int  M    = m;
      const auto walk = [&](int i0, int k0, int i1, int k1) {
        const int steps = std::max(std::abs(i1 - i0), std::abs(k1 - k0));
        for (int s = (path.empty() ? 0 : 1); s <= steps; ++s)
          path.emplace_back(i0 + (i1 - i0) * s / steps,
                            k0 + (k1 - k0) * s / steps);
      };
      if (quarters == 1)
        {
          walk(M, 0, M, M);
          walk(M, M, 0, M);
        }
      else if (quarters == 2)
        {
          walk(M, 0, M, M);
          walk(M, M, -M, M);
          walk(-M, M, -M, 0);
        }
      else
        {
          walk(M, 0, M, M);
          walk(M, M, -M, M);
          walk(-M, M, -M, -M);
          walk(-M, -M, M, -M);
          walk(M, -M, M, 0);
        }
      AssertThrow(path.size() == n_phi + 1, ExcInternalError());
    }

    // The x levels of the cores and their square grids.
    std::map<double, std::map<std::pair<int, int>, unsigned int>> square;
    std::map<double, unsigned int> circle_vertex; // x -> section vertex at r_c
    for (unsigned int q = 0; q < section.quads.size(); ++q)
      if (section.on_axis[q])
        for (const unsigned int v : section.quads[q])
          {
            const Point<2> &p = section.vertices[v];
            if (p[1] < tolerance)
              continue;
            circle_vertex[p[0]] = v;
            if (square.count(p[0]) == 0)
              for (int i = i_low; i <= int(m); ++i)
                for (int k = k_low; k <= int(m); ++k)
                  {
                    square[p[0]][{i, k}] = vertices.size();
                    vertices.emplace_back(p[0], a * i / m, a * k / m);
                    origin.emplace_back(-1, -1);
                  }
          }
    for (unsigned int q = 0; q < section.quads.size(); ++q)
      if (section.on_axis[q])
        {
          // the section quad's two x levels, and its circle vertices there
          std::array<double, 2>       x_level{};
          std::array<unsigned int, 2> on_circle{};
          unsigned int                found = 0;
          for (const unsigned int v : section.quads[q])
            if (section.vertices[v][1] > tolerance)
              {
                x_level[found]   = section.vertices[v][0];
                on_circle[found] = v;
                ++found;
              }
          AssertThrow(found == 2, ExcInternalError());
          if (x_level[0] > x_level[1])
            {
              std::swap(x_level[0], x_level[1]);
              std::swap(on_circle[0], on_circle[1]);
            }
          const auto &lower = square.at(x_level[0]);
          const auto &upper = square.at(x_level[1]);
          for (int i = i_low; i < int(m); ++i)
            for (int k = k_low; k < int(m); ++k)
              add_cell({{lower.at({i, k}),
                         lower.at({i + 1, k}),
                         lower.at({i, k + 1}),
                         lower.at({i + 1, k + 1}),
                         upper.at({i, k}),
                         upper.at({i + 1, k}),
                         upper.at({i, k + 1}),
                         upper.at({i + 1, k + 1})}},
                       section.materials[q],
                       false);
          for (unsigned int j = 0; j < n_phi; ++j)
            add_cell({{lower.at(path[j]),
                       lower.at(path[j + 1]),
                       at_angle(on_circle[0], j),
                       at_angle(on_circle[0], j + 1),
                       upper.at(path[j]),
                       upper.at(path[j + 1]),
                       at_angle(on_circle[1], j),
                       at_angle(on_circle[1], j + 1)}},
                     section.materials[q],
                     false);
        }

    // deal.II wants every cell with a positive measure and its vertices
    // numbered consistently between neighbours; the revolved cells' sense
    // depends on the section quadrilateral's. (GridTools::
    // invert_all_negative_measure_cells() accepts only meshes whose cells
    // all have the same sense, so cells of the wrong one swap their two
    // faces in the third direction here.)
    {
      std::vector<CellData<3>> ordered = cells;
      for (CellData<3> &cell : ordered)
        if (GridTools::cell_measure(
              vertices, ArrayView<const unsigned int>(cell.vertices)) < 0)
          for (unsigned int i = 0; i < 4; ++i)
            std::swap(cell.vertices[i], cell.vertices[i + 4]);
      GridTools::consistently_order_cells(ordered);
      triangulation.create_triangulation(vertices, ordered, SubCellData());
    }
    // consistently_order_cells() keeps the order of the cells.
    unsigned int index = 0;
    for (const auto &cell : triangulation.active_cell_iterators())
      {
        if (cell_revolved[index++])
          cell->set_all_manifold_ids(1);
      }
    triangulation.set_manifold(
      1, CylindricalManifold<3>(Tensor<1, 3>({1., 0., 0.}), Point<3>()));

    // <em>Boundary ids.</em>
    for (const auto &cell : triangulation.active_cell_iterators())
      for (const unsigned int f : cell->face_indices())
        if (cell->face(f)->at_boundary())
          {
            const auto    face = cell->face(f);
            std::set<int> section_vertices, angles;
            bool          core = false;
            for (const unsigned int i : face->vertex_indices())
              {
                const auto &o = origin[face->vertex_index(i)];
                if (o.first < 0)
                  core = true;
                section_vertices.insert(o.first);
                angles.insert(o.second);
              }
            const Point<3>     c          = face->center();
            types::boundary_id id         = numbers::invalid_boundary_id;
            const bool         on_plane_z = !full && std::abs(c[2]) < tolerance;
            const bool         on_plane_y =
              (quarters == 1) && std::abs(c[1]) < tolerance;
            if (on_plane_z)
              id = 4;
            else if (on_plane_y)
              id = 3;
            else if (core)
              {
                if (std::abs(c[0] - (design.x_end() - design.end_wall)) <
                    tolerance)
                  id = 2;
                else if (std::abs(c[0] - (design.x_end() +
                                          design.block_length)) < tolerance)
                  id = 5;
              }
            else if (section_vertices.size() == 2)
              {
                const auto edge  = std::make_pair(*section_vertices.begin(),
                                                 *section_vertices.rbegin());
                const auto found = section.boundary_edges.find(
                  {static_cast<unsigned int>(edge.first),
                   static_cast<unsigned int>(edge.second)});
                if (found != section.boundary_edges.end())
                  id = found->second;
              }
            AssertThrow(id != numbers::invalid_boundary_id,
                        ExcMessage("The bellows mesh has a boundary face at (" +
                                   std::to_string(c[0]) + ", " +
                                   std::to_string(c[1]) + ", " +
                                   std::to_string(c[2]) +
                                   ") that it cannot classify."));
            face->set_boundary_id(id);
          }
  }
} // namespace SoftRobot
