#include <springlab/net/exercises.hpp>

namespace springlab::net {

NetLayout buildNet(const NetParameters& p) {
  // TODO exercise 2.1 (building the net): write this part; see handouts/02_net.md, section Exercise 2.1.
  throw springlab::NotImplemented("2.1", "building the net", "handouts/02_net.md, section Exercise 2.1");
}

}  // namespace springlab::net
