#include "contact_figures.h"

#include <algorithm>
#include <iomanip>
#include <sstream>
#include <ostream>
#include <vector>

namespace fastcorot::cli {

json contacts_to_json(const CollisionStage<double>& stage) {
  const auto contacts = stage.contacts();
  json points = json::array(), normals = json::array();
  for (const DetectedContact<double>& contact : contacts) {
    points.push_back(points_to_json(std::span<const Vec3<double>>(contact.point, 2)));
    normals.push_back(points_to_json(std::span<const Vec3<double>>(&contact.normal, 1))[0]);
  }
  return {{"count", contacts.size()}, {"points", std::move(points)}, {"normals", std::move(normals)}};
}

std::string ContactTally::add(const CollisionReport& r) {
  ++steps;
  contacts += r.contacts;
  last = r.contacts;
  max_contacts = std::max<long>(max_contacts, r.contacts);
  model_pairs += r.model_pairs;
  element_pairs += r.element_pairs;
  degenerate = std::max<long>(degenerate, r.degenerate_elements);
  seconds += r.detection_seconds;
  if (r.crossed == 0) return {};
  const bool first = crossed == 0;
  crossed += r.crossed;
  deepest_crossing = std::max(deepest_crossing, r.deepest_crossing);
  if (!first) return {};
  first_crossing_step = steps;
  first_crossing_models = r.crossed_models;
  std::ostringstream line;
  line << "step " << steps << ": " << r.crossed << " contact(s) ended the step crossed, the deepest by " << r.deepest_crossing
       << " between " << r.crossed_models << " (deeper than the contact distance allows: a smaller time step, a larger "
       << "contactDistance or a stiffer contact would hold them; SOFA lets them pass silently)";
  return line.str();
}

void ContactTally::summarise(std::ostream& out) const {
  const double n = static_cast<double>(std::max<long>(steps, 1));
  out << "contacts: " << std::fixed << std::setprecision(1) << static_cast<double>(contacts) / n << " per step (at most "
      << max_contacts << ", last step " << last << "), " << static_cast<double>(element_pairs) / n
      << " element pairs tested per step, detection " << std::setprecision(3) << seconds << " s";
  if (degenerate > 0) out << "; " << degenerate << " degenerate element(s) skipped";
  if (crossed > 0) out << "; " << crossed << " crossed (deepest " << std::setprecision(3) << deepest_crossing << ")";
  out << '\n';
}

json ContactTally::to_json(double run_seconds) const {
  const double n = static_cast<double>(std::max<long>(steps, 1));
  return {{"last_step", last},
          {"max_per_step", max_contacts},
          {"mean_per_step", static_cast<double>(contacts) / n},
          {"model_pairs_per_step", static_cast<double>(model_pairs) / n},
          {"element_pairs_per_step", static_cast<double>(element_pairs) / n},
          {"degenerate_elements", degenerate},
          {"detection_seconds", seconds},
          {"detection_share", run_seconds > 0 ? seconds / run_seconds : 0.0},
          {"crossed", crossed},
          {"deepest_crossing", deepest_crossing}};
}

}  // namespace fastcorot::cli
