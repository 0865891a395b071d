# shaderlab for students and graders on any OS: the grader's own renderer (Mesa's llvmpipe), so a
# verdict in this container is the grader's verdict. Debian 13, built by the same setup script as
# everywhere else (grader-only: no window, no tests), run as a non-root user, the course mounted.
#
#   docker build -t shaderlab .
#   docker run --rm -it -v "$PWD":/course shaderlab shaderlab check 01-phong   # in the course's folder
#   docker run --rm -v "$PWD":/course shaderlab shaderlab grade work --out out/grade
#   docker run --rm -it -v "$PWD":/course shaderlab                            # a shell
#   docker run --rm -it -p 127.0.0.1:8420:8420 -v "$PWD":/course shaderlab \
#       shaderlab serve 01-phong --host 0.0.0.0    # the workbench: open http://127.0.0.1:8420/
# (inside the container serve must listen on every address to be reached through -p; the -p above
# publishes it on the host's loopback only, so nothing outside the laptop reaches it.)
#
# The course (the folder holding labs/) is found from the working folder upward, like git finds
# its repository; /course is the working folder. docs/students.md walks through it.
#
# The portable binary (scripts/portable-build.sh, without a chroot; docs/instructors.md), for any
# x86-64 Linux with glibc 2.31 or later: built on Debian 11, written to ./portable/shaderlab:
#   docker build --target portable-binary --output portable .
# (BuildKit, Docker's default builder, builds only the stages a target needs.)
FROM debian:bullseye-slim AS portable
COPY . /opt/shaderlab
RUN bash /opt/shaderlab/scripts/portable-build.sh --here /out

FROM scratch AS portable-binary
COPY --from=portable /out/shaderlab /shaderlab

# The student's image (the default target).
FROM debian:trixie-slim

COPY . /opt/shaderlab
RUN bash /opt/shaderlab/scripts/setup.sh --grader-only -DCMAKE_BUILD_TYPE=Release \
 && ln -s /opt/shaderlab/build/framework/shaderlab /usr/local/bin/shaderlab \
 && rm -rf /var/lib/apt/lists/* /opt/shaderlab/build/CMakeFiles \
 && useradd --create-home --uid 1000 student \
 && mkdir -p /course && chown student:student /course

USER student
WORKDIR /course
VOLUME /course
EXPOSE 8420
CMD ["bash"]
