// distribute: `raylane render` under mpirun: one job over the ranks of MPI_COMM_WORLD
// (render_job.h, render_over_mpi). Built when CMake finds MPI.
//
// The work is a list of units, a row of tiles of a frame each (or a piece of one, when there are
// many ranks), frame after frame. Units go out on demand: a worker keeps two asks open, so the
// next unit is known before it finishes the one in hand, and sends each unit's pixels without
// waiting for them to arrive. Rank 0 renders units too, on its main thread, while a service
// thread answers the asks, receives the pixels, puts them in their frame's film and writes a
// frame as soon as its last unit is in, with the very code of the plain render: so the file is
// the one a single process writes, byte for byte (a pixel's value does not depend on who renders
// its tile). Waits poll with a short pause: a blocking call of Open MPI spins, and would take a
// core from the ranks that render beside it.
//
// When a rank dies, mpirun stops the others with SIGTERM. Rank 0's handler then looks for the
// workers of its own host that are gone, and rank 0 prints one line: the lost rank, its host and
// the units it held, and that no image was written. When rank 0 itself fails (a frame it cannot
// write), it hands out no more units, lets the workers finish the ones they hold, and every rank
// ends normally; rank 0 prints the error.
#include <mpi.h>
#include <signal.h>
#include <tbb/info.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <exception>
#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "accel/bvh.h"
#include "core/clock.h"
#include "core/error.h"
#include "distribute/render_job.h"
#include "render/tiles.h"
#include "report/warnings.h"

namespace raylane {
namespace {

enum Tag : int {
    tag_ask = 1,     ///< worker -> 0: an int, ignored
    tag_unit = 2,    ///< 0 -> worker: the unit's index, or -1 when none is left
    tag_header = 3,  ///< worker -> 0: a ResultHeader
    tag_pixels = 4,  ///< worker -> 0: the unit's pixels (unit_floats)
};

/// A row of tiles, or a piece of one, of one frame.
struct Unit {
    int frame;
    PixelRect rect;
};

/// What a worker sends ahead of a unit's pixels: the unit and its counts.
struct ResultHeader {
    int64_t unit;
    uint64_t counts[7];  ///< RenderStats' ray and sample counts
    double seconds;
};

void to_header(int64_t unit, const RenderStats& s, ResultHeader& h) {
    h.unit = unit;
    const uint64_t c[7] = {s.primary_rays, s.shadow_rays, s.reflection_rays, s.refraction_rays,
                           s.glossy_rays,  s.nan_samples, s.inf_samples};
    std::memcpy(h.counts, c, sizeof c);
    h.seconds = s.seconds;
}

RenderStats from_header(const ResultHeader& h) {
    RenderStats s;
    s.primary_rays = h.counts[0], s.shadow_rays = h.counts[1], s.reflection_rays = h.counts[2];
    s.refraction_rays = h.counts[3], s.glossy_rays = h.counts[4], s.nan_samples = h.counts[5];
    s.inf_samples = h.counts[6], s.seconds = h.seconds;
    return s;
}

/// Units per rank and frame that make_units aims at: enough that the last units, which leave
/// ranks idle, are a small part of a frame...
constexpr int units_per_rank = 32;
/// ... as long as a unit keeps a rank's threads busy: this many tiles per thread at least.
constexpr int tiles_per_thread = 4;

/// Every unit of the job, frame after frame: the region's rows of tiles, each cut along the
/// tile grid into as many pieces as it takes for units_per_rank units per rank, if a piece
/// still holds tiles_per_thread tiles per thread (a 3840-pixel row over 64 ranks of 16 threads:
/// 3 pieces of 80 tiles).
std::vector<Unit> make_units(const RenderJob& job, int ranks) {
    const PixelRect whole{0, 0, job.still.width, job.still.height};
    const PixelRect r = job.region.empty() ? whole : job.region;
    const int tile = std::min(job.params.tile_size, 16);  // the packet renderer's grid
    const int gx0 = r.x0 - r.x0 % tile, gy0 = r.y0 - r.y0 % tile;
    const int rows = (r.y1 - gy0 + tile - 1) / tile, cols = (r.x1 - gx0 + tile - 1) / tile;
    const int threads =
        job.params.threads > 0 ? job.params.threads : tbb::info::default_concurrency();
    const int most = std::max(1, cols / (tiles_per_thread * threads));
    const int pieces = std::clamp((units_per_rank * ranks + rows - 1) / rows, 1, most);
    std::vector<Unit> units;
    for (int frame = job.first_frame; frame <= job.last_frame; ++frame) {
        for (int row = 0; row < rows; ++row) {
            const int y = gy0 + row * tile;
            for (int k = 0; k < pieces; ++k) {
                const int x0 = gx0 + k * cols / pieces * tile;
                const int x1 = gx0 + (k + 1) * cols / pieces * tile;
                units.push_back({frame,
                                 {std::max(x0, r.x0), std::max(y, r.y0), std::min(x1, r.x1),
                                  std::min(y + tile, r.y1)}});
            }
        }
    }
    return units;
}

/// The calling thread's CPU time in seconds: what serving costs the cores, without the time it
/// waits for one.
double thread_seconds() {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

/// A unit's films (one per AOV of the job) as one run of floats: film after film, each row by
/// row, 3 floats a pixel. What a worker sends.
std::vector<float> unit_floats(const PartResult& part) {
    static_assert(sizeof(vec3) == 3 * sizeof(float));
    std::vector<float> data;
    for (const AovFilm& f : part.films) {
        const float* p = reinterpret_cast<const float*>(f.film.pixels.data());
        data.insert(data.end(), p, p + f.film.pixels.size() * 3);
    }
    return data;
}

/// Rank 0's frames in progress: their films (the region's size, one per AOV) and the units
/// still missing.
struct Gather {
    Gather(const RenderJob& j, const PixelRect& r, int units)
        : job(j), region(r), units_per_frame(units) {}
    const RenderJob& job;
    PixelRect region;
    int units_per_frame;
    std::map<int, std::vector<AovFilm>> films;
    std::map<int, int> missing;
    std::map<int, RenderStats> stats;
    double start = now_seconds();
    double writing = 0.0;  ///< CPU seconds of this thread spent writing frames
    RenderStats total;     ///< every frame's counts

    /// Puts a unit's pixels in its frame, film k's from rgb[k] (row by row, 3 floats a pixel);
    /// writes the frame when it is whole (and returns true).
    bool add(int frame, const PixelRect& rect, const std::vector<const float*>& data,
             const RenderStats& s) {
        auto [it, fresh] = films.try_emplace(frame);
        if (fresh) {  // every pixel comes from some unit
            for (Aov aov : job.aovs) {
                it->second.push_back(
                    {aov, make_film_for_overwrite(region.width(), region.height())});
            }
            missing[frame] = units_per_frame;
        }
        for (size_t k = 0; k < it->second.size(); ++k) {
            Film& film = it->second[k].film;
            const float* rgb = data.at(k);
            for (int y = rect.y0; y < rect.y1; ++y) {
                std::memcpy(&film.at(rect.x0 - region.x0, y - region.y0),
                            rgb + size_t(y - rect.y0) * size_t(rect.width()) * 3,
                            size_t(rect.width()) * sizeof(vec3));
            }
        }
        RenderStats& fs = stats[frame];
        fs.add_counts(s);
        total.add_counts(s);
        if (--missing[frame] > 0) return false;
        // the frame is whole: its time is the wall time since the job (or the last frame) began
        fs.seconds = now_seconds() - start;
        start = now_seconds();
        const double t = thread_seconds();
        write_frame(job, frame, std::move(it->second), fs);
        writing += thread_seconds() - t;
        films.erase(frame), missing.erase(frame), stats.erase(frame);
        return true;
    }
};

/// Where a rank runs: what rank 0 names a lost rank by, and looks for it with.
struct RankPlace {
    char host[64];
    int32_t pid;
};

/// Every rank's place, on rank 0 (empty on the others).
std::vector<RankPlace> gather_places(int rank, int ranks) {
    RankPlace mine{};
    gethostname(mine.host, sizeof mine.host - 1);
    mine.pid = static_cast<int32_t>(getpid());
    std::vector<RankPlace> all(rank == 0 ? size_t(ranks) : 0);
    MPI_Gather(&mine, sizeof mine, MPI_BYTE, all.data(), sizeof mine, MPI_BYTE, 0, MPI_COMM_WORLD);
    return all;
}

/// Rank 0's record of the job: who holds each unit, and how many frames are written. What it says
/// when the job is stopped.
struct JobRecord {
    static constexpr int waiting = -1;   ///< not handed out yet
    static constexpr int gathered = -2;  ///< its pixels are in their frame
    std::vector<int> holder;             ///< per unit: the rank rendering it, or the above
    std::atomic<int> frames_written{0};  ///< frames written (read by the stop handler)
};

/// A line of text built without allocating: the stop handler's (async-signal-safe).
struct FixedLine {
    char text[4096];
    size_t size = 0;
    FixedLine& operator<<(const char* s) {
        while (*s != '\0' && size + 2 < sizeof text) text[size++] = *s++;
        return *this;
    }
    FixedLine& operator<<(long v) {
        char digits[24];
        int n = 0;
        unsigned long u =
            v < 0 ? 0ul - static_cast<unsigned long>(v) : static_cast<unsigned long>(v);
        do digits[n++] = static_cast<char>('0' + u % 10);
        while ((u /= 10) != 0);
        if (v < 0) *this << "-";
        while (n > 0 && size + 2 < sizeof text) text[size++] = digits[--n];
        return *this;
    }
};

/// What the stop handler reads and writes: set before the render, read in the handler.
namespace stop {
constexpr int max_ranks = 4096;
int ranks = 0;
pid_t local_pid[max_ranks];  ///< the workers on rank 0's host; 0 for the others
volatile std::sig_atomic_t gone[max_ranks];
volatile std::sig_atomic_t signal_number = 0;
volatile std::sig_atomic_t rendering = 0;  ///< 1 once the units are being rendered
bool speaks = false;                       ///< rank 0
const RenderJob* job = nullptr;
const Unit* units = nullptr;
size_t unit_count = 0;
const RankPlace* places = nullptr;
const JobRecord* record = nullptr;
}  // namespace stop

/// Adds the units rank r holds, as "frame F rows A-B" (no frame for a still; columns when the
/// unit is a piece of a row), at most four and then how many more.
void add_held_units(FixedLine& line, int r) {
    if (stop::record == nullptr) {  // before the render
        line << "no unit yet";
        return;
    }
    const RenderJob& job = *stop::job;
    const int full_width = job.region.empty() ? job.still.width : job.region.width();
    long n = 0;
    for (size_t u = 0; u < stop::unit_count; ++u) {
        if (stop::record->holder[u] != r || n++ >= 4) continue;
        const Unit& unit = stop::units[u];
        line << (n > 1 ? ", " : "");
        if (job.first_frame != job.last_frame) line << "frame " << long(unit.frame) << " ";
        line << "rows " << long(unit.rect.y0) << "-" << long(unit.rect.y1 - 1);
        if (unit.rect.width() != full_width)
            line << " x " << long(unit.rect.x0) << "-" << long(unit.rect.x1 - 1);
    }
    if (n == 0) line << "no unit";
    if (n > 4) line << " and " << (n - 4) << " more units";
}

/// Adds what was written before the job stopped.
void add_written(FixedLine& line) {
    const int n = stop::record != nullptr ? stop::record->frames_written.load() : 0;
    if (n == 0) {
        line << "no image was written";
    } else {
        line << long(n) << (n == 1 ? " frame was" : " frames were") << " written, no other";
    }
}

/// Rank 0's line when the job is stopped: the lost workers of its host, with what they held; or,
/// when none of them is gone (a rank on another host, or an interrupt), the signal and who held
/// what.
void write_stopped_line(int sig) {
    FixedLine line;
    line << "raylane: ";
    bool lost = false;
    for (int r = 1; r < stop::ranks; ++r) {
        if (!stop::gone[r]) continue;
        line << (lost ? "; " : "") << "rank " << long(r) << " (host " << stop::places[r].host
             << ", pid " << long(stop::places[r].pid) << ") was lost while it held ";
        add_held_units(line, r);
        lost = true;
    }
    if (lost) {
        line << "; mpirun stopped the other ranks and ";
        add_written(line);
    } else {
        line << "stopped by signal " << long(sig)
             << " (mpirun stops every rank when one is lost or the job is interrupted; its own "
                "message names the rank) before the job was done; ";
        add_written(line);
        for (int r = 1; r < stop::ranks && stop::record != nullptr; ++r) {
            line << "; rank " << long(r) << " (host " << stop::places[r].host << ") held ";
            add_held_units(line, r);
        }
    }
    line.text[line.size++] = '\n';
    (void)!write(STDERR_FILENO, line.text, line.size);
}

/// SIGTERM or SIGINT under mpirun, which sends SIGTERM to every rank when one dies. Rank 0 looks
/// for the workers of its host that no longer exist (mpirun has reaped a lost one before it
/// stops the others) and says so at once: mpirun stops forwarding a rank's output soon after.
/// Then the render stops at the next tile, and the process ends (render_over_mpi).
extern "C" void on_stop_under_mpi(int sig) {
    const int saved = errno;
    stop::signal_number = sig;
    for (int r = 1; r < stop::ranks; ++r)
        if (stop::local_pid[r] > 0 && kill(stop::local_pid[r], 0) != 0 && errno == ESRCH)
            stop::gone[r] = 1;
    if (stop::speaks) write_stopped_line(sig);
    if (!stop::rendering) _exit(128 + sig);  // loading or building: nothing to stop at
    request_cancel();
    std::signal(sig, SIG_DFL);  // the next one terminates
    errno = saved;
}

/// Gives the stop handler every rank's place, and the workers of rank 0's host to watch.
void watch_ranks(const std::vector<RankPlace>& places) {
    stop::places = places.data();
    stop::ranks = std::min<int>(static_cast<int>(places.size()), stop::max_ranks);
    for (int r = 1; r < stop::ranks; ++r) {
        const bool here =
            std::strncmp(places[size_t(r)].host, places[0].host, sizeof places[0].host) == 0;
        stop::local_pid[r] = here ? static_cast<pid_t>(places[size_t(r)].pid) : 0;
    }
}

/// Gives the stop handler the job, its units and who holds them: what a lost rank held.
void watch_units(const RenderJob& job, const std::vector<Unit>& units, const JobRecord& record) {
    stop::job = &job, stop::units = units.data(), stop::unit_count = units.size();
    stop::record = &record;
}

/// A pause between two polls of a wait: a blocking MPI call polls without one, and takes a core
/// from the ranks that render beside it.
void pause() { std::this_thread::sleep_for(std::chrono::microseconds(1000)); }

/// Waits for n requests, pausing between polls; throws Cancelled when the job is stopped.
void wait_all(MPI_Request* requests, int n) {
    for (;;) {
        int done = 0;
        MPI_Testall(n, requests, &done, MPI_STATUSES_IGNORE);
        if (done) return;
        if (cancel_requested()) throw Cancelled();
        pause();
    }
}

/// Receives a unit's index from rank 0.
void receive_unit(int& unit) {
    MPI_Request request;
    MPI_Irecv(&unit, 1, MPI_INT, 0, tag_unit, MPI_COMM_WORLD, &request);
    wait_all(&request, 1);
}

/// What distribution cost: seconds spent in MPI calls and in copying pixels, and rows rendered.
struct MpiCosts {
    double serving = 0.0;  ///< rank 0: answering and gathering while it could render (not
                           ///< writing frames)
    double waiting = 0.0;  ///< rank 0 after its last unit; a worker in its sends and receives
    int64_t units = 0;     ///< units rendered by this rank
    RenderStats total;     ///< rank 0: every frame's counts
};

/// Asks a worker keeps open: the answer to one is on its way while it renders another.
constexpr int asks_ahead = 2;

/// Rank 0's service: answers every ask, receives the workers' pixels without blocking (a large
/// message may need its sender, busy rendering, to move it), takes rank 0's own results from
/// `take_own(add)` (which returns true once rank 0 renders no more), gathers and writes the
/// frames. Returns the CPU seconds spent handling messages and pixels (not writing frames, not
/// pausing); `total` gets every frame's counts. If a frame cannot be written, hands out no more
/// units, receives (and drops) those the workers hold, then throws the error. Throws Cancelled
/// when the job is stopped, and returns at once when `quit` is set.
template <class TakeOwn>
double serve_workers(const RenderJob& job, const std::vector<Unit>& units, int ranks,
                     bool show_progress, std::atomic<size_t>& next, const std::atomic<bool>& quit,
                     JobRecord& record, RenderStats& total, TakeOwn&& take_own) {
    Gather gather(
        job, job.region.empty() ? PixelRect{0, 0, job.still.width, job.still.height} : job.region,
        static_cast<int>(units.size()) / (job.last_frame - job.first_frame + 1));
    Progress progress{"render", units.size(), show_progress && stderr_is_terminal()};
    int nones_left = asks_ahead * (ranks - 1);  // every worker's last asks are answered "none"
    size_t gathered = 0, handed_out = 0, received = 0;  // handed out to and received from workers
    std::exception_ptr failure;                         // a frame that could not be written
    struct Receiving {
        ResultHeader header;
        std::vector<float> pixels;
        MPI_Request request;
    };
    std::vector<std::unique_ptr<Receiving>> receiving;
    auto add = [&](size_t unit, const std::vector<const float*>& data, const RenderStats& stats) {
        record.holder[unit] = JobRecord::gathered;
        ++gathered;
        if (failure) return;
        try {
            if (gather.add(units[unit].frame, units[unit].rect, data, stats))
                ++record.frames_written;
            progress.step();
        } catch (const std::exception&) {
            failure = std::current_exception();
            next.store(units.size());  // no more units, to anyone
        }
    };
    auto more = [&](bool own_done) {
        if (!own_done || nones_left > 0) return true;
        return failure ? received < handed_out : gathered < units.size();
    };
    double busy = 0.0;
    bool own_done = false;
    while (more(own_done)) {
        if (quit.load()) return busy;
        if (cancel_requested()) throw Cancelled();
        const double t = thread_seconds(), written = gather.writing;
        bool any = false;
        for (;;) {
            int ready = 0;
            MPI_Status st;
            MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &ready, &st);
            if (!ready) break;
            any = true;
            if (st.MPI_TAG == tag_ask) {
                int ignored = 0;
                MPI_Recv(&ignored, 1, MPI_INT, st.MPI_SOURCE, tag_ask, MPI_COMM_WORLD,
                         MPI_STATUS_IGNORE);
                const size_t u = next.fetch_add(1);
                int unit = u < units.size() ? static_cast<int>(u) : -1;
                if (unit < 0) {
                    --nones_left;
                } else {
                    record.holder[u] = st.MPI_SOURCE;
                    ++handed_out;
                }
                MPI_Send(&unit, 1, MPI_INT, st.MPI_SOURCE, tag_unit, MPI_COMM_WORLD);
            } else if (st.MPI_TAG == tag_header) {
                auto r = std::make_unique<Receiving>();
                MPI_Recv(&r->header, sizeof r->header, MPI_BYTE, st.MPI_SOURCE, tag_header,
                         MPI_COMM_WORLD, MPI_STATUS_IGNORE);
                const Unit& u = units.at(size_t(r->header.unit));
                r->pixels.resize(size_t(u.rect.width()) * size_t(u.rect.height()) * 3 *
                                 job.aovs.size());
                MPI_Irecv(r->pixels.data(), static_cast<int>(r->pixels.size()), MPI_FLOAT,
                          st.MPI_SOURCE, tag_pixels, MPI_COMM_WORLD, &r->request);
                receiving.push_back(std::move(r));
            } else {
                throw std::runtime_error("MPI: unexpected message");
            }
        }
        std::erase_if(receiving, [&](std::unique_ptr<Receiving>& r) {
            int done = 0;
            MPI_Test(&r->request, &done, MPI_STATUS_IGNORE);
            if (done) {
                const Unit& u = units[size_t(r->header.unit)];
                const size_t per_film = size_t(u.rect.width()) * size_t(u.rect.height()) * 3;
                std::vector<const float*> data;
                for (size_t k = 0; k < job.aovs.size(); ++k)
                    data.push_back(r->pixels.data() + k * per_film);
                ++received;
                add(size_t(r->header.unit), data, from_header(r->header));
            }
            any = any || done != 0;
            return done != 0;
        });
        own_done = take_own([&](size_t unit, const PartResult& r) {
            std::vector<const float*> data;
            for (const AovFilm& f : r.films)
                data.push_back(reinterpret_cast<const float*>(f.film.pixels.data()));
            add(unit, data, r.stats);
            any = true;
        });
        if (any) {
            busy += thread_seconds() - t - (gather.writing - written);
        } else {
            pause();
        }
    }
    if (failure) std::rethrow_exception(failure);
    progress.finish();
    total = gather.total;
    return busy;
}

/// Rank 0: a service thread answers the workers as their asks come, gathers the pixels and
/// writes the frames, while the main thread renders units from the same list. Only the service
/// thread calls MPI while both run (MPI_THREAD_SERIALIZED). Both threads end on every path out.
MpiCosts run_rank0(RenderJob& job, const std::vector<Unit>& units, int ranks, bool show_progress,
                   JobRecord& record) {
    MpiCosts costs;
    std::atomic<size_t> next{0};  // the next unit to hand out, to a worker or to rank 0
    std::atomic<bool> quit{false};
    // rank 0's own results, from the main thread to the service thread
    struct Own {
        size_t unit;
        PartResult result;
    };
    std::mutex own_mutex;
    std::vector<Own> own;
    bool own_done = false;

    std::exception_ptr service_error;
    std::thread service([&] {
        try {
            costs.serving = serve_workers(job, units, ranks, show_progress, next, quit, record,
                                          costs.total, [&](auto&& add) {
                                              std::vector<Own> mine;
                                              bool done = false;
                                              {
                                                  std::lock_guard<std::mutex> lock(own_mutex);
                                                  mine.swap(own);
                                                  done = own_done;
                                              }
                                              for (Own& o : mine) add(o.unit, o.result);
                                              return done;
                                          });
        } catch (...) {
            service_error = std::current_exception();
        }
    });
    try {
        for (;;) {
            const size_t u = next.fetch_add(1);
            if (u >= units.size()) break;
            record.holder[u] = 0;
            PartResult r = render_part(job, units[u].frame, units[u].rect);
            ++costs.units;
            std::lock_guard<std::mutex> lock(own_mutex);
            own.push_back({u, std::move(r)});
        }
    } catch (...) {
        quit.store(true);
        service.join();
        throw;
    }
    const double t = now_seconds();
    {
        std::lock_guard<std::mutex> lock(own_mutex);
        own_done = true;
    }
    service.join();
    costs.waiting = now_seconds() - t;  // after rank 0's last unit
    if (service_error) std::rethrow_exception(service_error);
    return costs;
}

/// A worker: keeps asks_ahead asks open, renders what comes, sends each unit's pixels without
/// waiting for them to arrive (rank 0 takes them between its own units).
MpiCosts run_worker(RenderJob& job, const std::vector<Unit>& units) {
    struct Sent {
        std::vector<float> data;  ///< unit_floats
        ResultHeader header;
        MPI_Request requests[2];
    };
    MpiCosts costs;
    std::vector<std::unique_ptr<Sent>> sent;  // in flight; the buffers stay where they are
    int ask = 0, unit = -1;
    double t = now_seconds();
    for (int i = 0; i < asks_ahead; ++i) MPI_Send(&ask, 1, MPI_INT, 0, tag_ask, MPI_COMM_WORLD);
    for (;;) {
        receive_unit(unit);
        if (unit < 0) break;
        MPI_Send(&ask, 1, MPI_INT, 0, tag_ask, MPI_COMM_WORLD);
        costs.waiting += now_seconds() - t;
        const Unit& u = units.at(size_t(unit));
        const PartResult part = render_part(job, u.frame, u.rect);
        ++costs.units;
        t = now_seconds();
        auto s = std::make_unique<Sent>();
        s->data = unit_floats(part);
        to_header(unit, part.stats, s->header);
        MPI_Isend(&s->header, sizeof s->header, MPI_BYTE, 0, tag_header, MPI_COMM_WORLD,
                  &s->requests[0]);
        MPI_Isend(s->data.data(), static_cast<int>(s->data.size()), MPI_FLOAT, 0, tag_pixels,
                  MPI_COMM_WORLD, &s->requests[1]);
        sent.push_back(std::move(s));
        // free what has arrived
        std::erase_if(sent, [](std::unique_ptr<Sent>& p) {
            int done = 0;
            MPI_Testall(2, p->requests, &done, MPI_STATUSES_IGNORE);
            return done != 0;
        });
    }
    for (int i = 1; i < asks_ahead; ++i)  // the other open asks are answered "none" too
        receive_unit(unit);
    for (std::unique_ptr<Sent>& p : sent) wait_all(p->requests, 2);
    costs.waiting += now_seconds() - t;
    return costs;
}

/// Whether every rank succeeded; otherwise the lowest rank that failed prints its line.
bool all_succeeded(const std::string& error, int rank) {
    const int mine = error.empty() ? 1 << 30 : rank;
    int first = 0;
    MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
    if (first == rank) std::fprintf(stderr, "raylane: %s\n", error.c_str());
    return first == 1 << 30;
}

}  // namespace

int render_over_mpi(const std::function<RenderJob()>& make_job) {
    int provided = 0;
    MPI_Init_thread(nullptr, nullptr, MPI_THREAD_SERIALIZED, &provided);
    int rank = 0, ranks = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &ranks);
    stop::speaks = rank == 0;
    std::signal(SIGTERM, on_stop_under_mpi);
    std::signal(SIGINT, on_stop_under_mpi);
    RenderJob job;
    std::string error;
    try {
        if (provided < MPI_THREAD_SERIALIZED)
            throw InputError(
                "this MPI library runs no threads beside MPI calls (it gives no "
                "MPI_THREAD_SERIALIZED), which rank 0 needs");
        job = make_job();
    } catch (const InputError& e) {
        error = e.what();
    }
    if (!all_succeeded(error, rank)) {
        MPI_Finalize();
        return 2;
    }
    const std::vector<RankPlace> places = gather_places(rank, ranks);
    watch_ranks(places);
    // only rank 0 speaks: the others' output would interleave with its own
    if (rank == 0) print_header(job, ranks);
    const double t_build = now_seconds();
    job.accel = build_accel(job.scene, build_params(job.bvh));
    job.build_ms = elapsed_ms(t_build);
    if (rank == 0) {
        for (const std::string& w : scene_warnings(job.scene, job.accel))
            std::printf("warning    %s\n", w.c_str());
        std::fflush(stdout);
    }
    // the renderers' own progress would be a unit's: rank 0 shows the job's
    const bool progress = rank == 0 && job.params.progress;
    job.params.progress = false;
    const std::vector<Unit> units = make_units(job, ranks);
    const double start = now_seconds();
    JobRecord record;
    record.holder.assign(units.size(), JobRecord::waiting);
    watch_units(job, units, record);
    MpiCosts mine;
    stop::rendering = 1;
    std::string failure;  // rank 0 could not write a frame: the others end normally
    try {
        mine = rank == 0 ? run_rank0(job, units, ranks, progress, record) : run_worker(job, units);
    } catch (const Cancelled&) {
        // mpirun is stopping every rank (rank 0's handler has said why): out before its SIGKILL
        std::fflush(stdout);
        std::_Exit(128 + (stop::signal_number != 0 ? int(stop::signal_number) : SIGTERM));
    } catch (const std::exception& e) {
        if (rank != 0) throw;
        failure = e.what();
    }
    const double seconds = now_seconds() - start;
    // what distribution cost, summed over the workers
    double waited = rank == 0 ? 0.0 : mine.waiting, workers_waited = 0.0;
    MPI_Reduce(&waited, &workers_waited, 1, MPI_DOUBLE, MPI_SUM, 0, MPI_COMM_WORLD);
    if (rank == 0 && !failure.empty()) {
        MPI_Finalize();
        FixedLine line;
        line << "raylane: " << failure.c_str() << "; ";
        add_written(line);
        std::fprintf(stderr, "%.*s\n", static_cast<int>(line.size), line.text);
        return 1;
    }
    if (rank == 0 && !job.quiet) {
        std::printf(
            "ranks      %d; rank 0 rendered %lld of %zu units, spent %.1f ms "
            "handing out and gathering, %.1f ms waiting for the last units; the "
            "workers waited %.1f ms in all (%.1f %% of their time)\n",
            ranks, static_cast<long long>(mine.units), units.size(), 1000.0 * mine.serving,
            1000.0 * mine.waiting, 1000.0 * workers_waited,
            100.0 * workers_waited / (seconds * double(ranks - 1)));
    }
    MPI_Finalize();
    return rank == 0 ? strict_exit_code(job, mine.total) : 0;
}

}  // namespace raylane
