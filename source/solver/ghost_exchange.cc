#include <talus/solver/ghost_exchange.h>
#include <talus/solver/rigid_solver.h>

#include <algorithm>
#include <cstdint>
#include <stdexcept>

namespace talus
{

RankReductions reductions_over(MPI_Comm comm)
{
  RankReductions r;
  r.any = [comm](bool x)
  {
    int in = x ? 1 : 0, out = 0;
    MPI_Allreduce(&in, &out, 1, MPI_INT, MPI_LOR, comm);
    return out != 0;
  };
  r.min = [comm](double x)
  {
    double out = x;
    MPI_Allreduce(&x, &out, 1, MPI_DOUBLE, MPI_MIN, comm);
    return out;
  };
  r.max = [comm](double x)
  {
    double out = x;
    MPI_Allreduce(&x, &out, 1, MPI_DOUBLE, MPI_MAX, comm);
    return out;
  };
  r.sum = [comm](ExactSum& s)
  {
    s.normalize();
    MPI_Allreduce(MPI_IN_PLACE, s.words().data(), ExactSum::n_words, MPI_INT64_T, MPI_SUM, comm);
    MPI_Allreduce(MPI_IN_PLACE, s.special().data(), 3, MPI_INT64_T, MPI_SUM, comm);
  };
  r.sums = [comm](std::vector<ExactSum>& sums)
  {
    std::vector<std::int64_t> words;
    for (ExactSum& s : sums)
    {
      s.normalize();
      words.insert(words.end(), s.words().begin(), s.words().end());
      words.insert(words.end(), s.special().begin(), s.special().end());
    }
    MPI_Allreduce(MPI_IN_PLACE, words.data(), static_cast<int>(words.size()), MPI_INT64_T, MPI_SUM,
                  comm);
    const std::int64_t* at = words.data();
    for (ExactSum& s : sums)
    {
      std::copy(at, at + ExactSum::n_words, s.words().begin());
      at += ExactSum::n_words;
      std::copy(at, at + 3, s.special().begin());
      at += 3;
    }
  };
  return r;
}

void GhostExchange::refresh(RigidSolver& solver)
{
  const int tag = 2401;
  std::vector<MPI_Request> requests;
  in_.resize(blocks_.receive.size());
  out_.resize(blocks_.send.size());
  for (std::size_t k = 0; k < blocks_.receive.size(); ++k)
  {
    const auto& [from, ghosts] = blocks_.receive[k];
    std::size_t size = 0;
    for (unsigned int i : ghosts)
      size += solver.packed_size(i);
    in_[k].resize(size);
    requests.emplace_back();
    MPI_Irecv(in_[k].data(), static_cast<int>(size), MPI_DOUBLE, static_cast<int>(from), tag, comm_,
              &requests.back());
  }
  sent_ = 0;
  for (std::size_t k = 0; k < blocks_.send.size(); ++k)
  {
    const auto& [to, mine] = blocks_.send[k];
    out_[k].clear();
    for (unsigned int i : mine)
      solver.pack_block(i, out_[k]);
    sent_ += out_[k].size();
    requests.emplace_back();
    MPI_Isend(out_[k].data(), static_cast<int>(out_[k].size()), MPI_DOUBLE, static_cast<int>(to),
              tag, comm_, &requests.back());
  }
  if (MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE) !=
      MPI_SUCCESS)
    throw std::runtime_error("GhostExchange: a message between ranks failed");
  for (std::size_t k = 0; k < blocks_.receive.size(); ++k)
  {
    const double* at = in_[k].data();
    for (unsigned int i : blocks_.receive[k].second)
      at = solver.unpack_block(i, at);
  }
}

} // namespace talus
