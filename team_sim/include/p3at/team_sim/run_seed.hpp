#pragma once
/// Run i's seed in a campaign: the same whether the campaign runs on one
/// machine or as shards on many (campaign.hpp, campaign_part.hpp).

#include <cstdint>

namespace p3at::team_sim {

/// The i-th output of SplitMix64 (Steele, Lea, Flood 2014) seeded with
/// `campaign_seed`: well-mixed seeds, so campaigns with nearby seeds share
/// no runs. Any run can be replayed alone: `vipars simulate --runs 1
/// --seed <run's seed>`.
std::uint64_t run_seed(std::uint64_t campaign_seed, std::uint64_t run_index);

}  // namespace p3at::team_sim
