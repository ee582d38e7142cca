#include "friction_study_record.h"

#include "json_number.h"

namespace fibrecheck {

using nlohmann::json;

json to_json(const FrictionPoint& p) {
  return {{"fibres", p.fibres},
          {"compaction", p.compaction},
          {"mu", p.mu},
          {"friction_model", p.model},
          {"fibre_volume_fraction", p.fibre_volume_fraction},
          {"status", p.status},
          {"criterion", p.criterion},
          {"message", p.message},
          {"iterations", p.iterations},
          {"geometric_updates", p.geometric_updates},
          {"time_s", p.time_s},
          {"stick_residual", number_or_null(p.stick_residual)},
          {"slip_residual", number_or_null(p.slip_residual)},
          {"pressure", number_or_null(p.pressure)}};
}

void from_json(const json& j, FrictionPoint& p) {
  p.fibres = j.at("fibres");
  p.compaction = j.at("compaction");
  p.mu = j.at("mu");
  p.model = j.at("friction_model");
  p.fibre_volume_fraction = j.at("fibre_volume_fraction");
  p.status = j.at("status");
  p.criterion = j.at("criterion");
  p.message = j.at("message");
  p.iterations = j.at("iterations");
  p.geometric_updates = j.at("geometric_updates");
  p.time_s = j.at("time_s");
  p.stick_residual = number_at(j, "stick_residual");
  p.slip_residual = number_at(j, "slip_residual");
  p.pressure = number_at(j, "pressure");
}

}  // namespace fibrecheck
