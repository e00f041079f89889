#include <springlab/net/exercises.hpp>

namespace springlab::net {

NetLayout buildNet(const NetParameters& p) {
  // TODO exercise 2.1 (building the net): write this part; see handouts/02_net.md, Exercise 2.1 (physics in section 2.a, The grid and its three kinds of springs).
  throw springlab::NotImplemented("2.1", "building the net", "handouts/02_net.md, Exercise 2.1 (physics in section 2.a, The grid and its three kinds of springs)");
}

}  // namespace springlab::net
