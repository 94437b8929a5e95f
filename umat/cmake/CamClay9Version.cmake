# The project's version, one place for both ways of building (included before project()).
set(CAMCLAY9_VERSION 0.1.0)
