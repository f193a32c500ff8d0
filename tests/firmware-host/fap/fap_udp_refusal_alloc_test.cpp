// A datagram from a sender off the FAP stream's allow list is refused before
// anything is allocated for it or parsed (docs/FAP.md, "Who may send"): a
// flood from a foreign address costs the receiver no heap. In the allocation
// test binary, which counts the C allocator's calls (support/allocation_counter).
#include <gtest/gtest.h>
#include <poll.h>

#include "default_fap_head.hpp"
#include "firmware-host/fap/fap_udp_stream.hpp"
#include "tests/support/allocation_counter.hpp"
#include "udp_sender.hpp"

namespace facectl {
namespace {

using testing::begin_counting_allocations;
using testing::default_fap_head;
using testing::end_counting_allocations;
using testing::Sender;

// Polls the one datagram `from` sends, counting the allocations.
long allocations_to_poll_one_from(const char* from, FapUdpStream& stream) {
  Sender tx(stream.port(), from);
  tx.send("2.1 a-name-longer-than-any-small-string-buffer 25 0\n");
  pollfd p{stream.fd(), POLLIN, 0};
  EXPECT_EQ(::poll(&p, 1, 2000), 1) << "the datagram never arrived";
  begin_counting_allocations();
  stream.poll();
  return end_counting_allocations();
}

TEST(FapUdpRefusal, ASenderOffTheAllowListCostsNoAllocation) {
  FapUdpOptions o;
  o.allow = {*parse_udp_sender_rule("127.0.0.2")};
  FapUdpStream stream(default_fap_head().mapping, o);
  EXPECT_EQ(allocations_to_poll_one_from("127.0.0.1", stream), 0);
  EXPECT_EQ(stream.stats().refused_senders, 1u);
  // The count works: an allowed sender's datagram is parsed, which allocates.
  EXPECT_GT(allocations_to_poll_one_from("127.0.0.2", stream), 0);
  EXPECT_EQ(stream.stats().refused_senders, 1u);
}

}  // namespace
}  // namespace facectl
