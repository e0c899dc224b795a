#pragma once
// Until issue 17 lands on main (the calibration rig, the validation documents
// and the report become libraries there): the same header from apps/vipars.
#include "../../../../apps/vipars/report_build.hpp"
