#include "decompose/kinematics_table.h"

#include <algorithm>
#include <charconv>
#include <cmath>

namespace lcnc::decompose {

void fill_derivatives(KinematicsTable& t, double v0_main, double v0_aux) {
  const std::size_t n = t.size();
  for (auto* v : {&t.v_main, &t.v_aux, &t.at_main, &t.at_aux, &t.a_main, &t.a_aux, &t.a_eff}) {
    v->assign(n, 0.0);
  }
  if (n == 0) return;
  t.v_main[0] = v0_main;
  t.v_aux[0] = v0_aux;
  for (std::size_t i = 1; i < n; ++i) {
    const double dt = t.t_s[i] - t.t_s[i - 1];
    if (dt <= 0.0) {
      t.v_main[i] = t.v_main[i - 1];
      t.v_aux[i] = t.v_aux[i - 1];
      continue;
    }
    t.v_main[i] = (t.main[i] - t.main[i - 1]).norm() / dt;
    t.v_aux[i] = (t.aux(i) - t.aux(i - 1)).norm() / dt;
    t.at_main[i] = (t.v_main[i] - t.v_main[i - 1]) / dt;
    t.at_aux[i] = (t.v_aux[i] - t.v_aux[i - 1]) / dt;
  }
  for (std::size_t i = 1; i + 1 < n; ++i) {
    const double dt0 = t.t_s[i] - t.t_s[i - 1];
    const double dt1 = t.t_s[i + 1] - t.t_s[i];
    if (dt0 <= 0.0 || dt1 <= 0.0) continue;
    const double h = 0.5 * (dt0 + dt1);
    auto acc = [&](const Vec2& a, const Vec2& b, const Vec2& c) {
      return ((c - b) / dt1 - (b - a) / dt0).norm() / h;
    };
    t.a_main[i] = acc(t.main[i - 1], t.main[i], t.main[i + 1]);
    t.a_aux[i] = acc(t.aux(i - 1), t.aux(i), t.aux(i + 1));
    t.a_eff[i] = acc(t.beam[i - 1], t.beam[i], t.beam[i + 1]);
  }
}

double loop_accel(const std::vector<Vec2>& x, const std::vector<double>& t_s, std::size_t first,
                  std::size_t last) {
  const double dt0 = t_s[last] - t_s[last - 1];
  const double dt1 = t_s[first + 1] - t_s[first];
  if (dt0 <= 0.0 || dt1 <= 0.0) return 0.0;
  return ((x[first + 1] - x[first]) / dt1 - (x[last] - x[last - 1]) / dt0).norm() / (0.5 * (dt0 + dt1));
}

Peaks peaks(const KinematicsTable& t) {
  Peaks p;
  for (std::size_t i = 0; i < t.size(); ++i) {
    p.v_main = std::max(p.v_main, t.v_main[i]);
    p.v_aux = std::max(p.v_aux, t.v_aux[i]);
    p.a_main = std::max(p.a_main, t.a_main[i]);
    p.a_aux = std::max(p.a_aux, t.a_aux[i]);
    p.a_eff = std::max(p.a_eff, t.a_eff[i]);
    const Vec2 a = t.aux(i);
    p.aux_excursion = std::max({p.aux_excursion, std::abs(a.x()), std::abs(a.y())});
    p.exactness = std::max(p.exactness, (t.main[i] + a - t.beam[i]).norm());
  }
  if (!t.t_s.empty()) p.duration_s = t.t_s.back() - t.t_s.front();
  return p;
}

namespace {

void put(std::string& s, double v, int decimals) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed, decimals);
  s.append(buf, r.ptr);
}

}  // namespace

void write_csv(std::ostream& out, const std::vector<const KinematicsTable*>& tables) {
  out << "contour,i,x_mm,y_mm,p_mm,q_mm,t_s,v_main_mm_s,v_aux_mm_s,a_main_mm_s2,a_aux_mm_s2,"
         "at_main_mm_s2,at_aux_mm_s2,a_eff_mm_s2,sx_mm,sy_mm\n";
  std::string row;
  for (const KinematicsTable* t : tables) {
    for (std::size_t i = 0; i < t->size(); ++i) {
      row.clear();
      row += std::to_string(t->contour);
      row += ',';
      row += std::to_string(i);
      const Vec2 a = t->aux(i);
      for (double v : {t->main[i].x(), t->main[i].y(), a.x(), a.y()}) {
        row += ',';
        put(row, v, 6);
      }
      row += ',';
      put(row, t->t_s[i], 9);
      for (double v :
           {t->v_main[i], t->v_aux[i], t->a_main[i], t->a_aux[i], t->at_main[i], t->at_aux[i], t->a_eff[i]}) {
        row += ',';
        put(row, v, 3);
      }
      for (double v : {t->beam[i].x(), t->beam[i].y()}) {
        row += ',';
        put(row, v, 6);
      }
      row += '\n';
      out << row;
    }
  }
}

}  // namespace lcnc::decompose
