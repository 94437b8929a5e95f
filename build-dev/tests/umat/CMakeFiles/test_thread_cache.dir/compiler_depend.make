# Empty compiler generated dependencies file for test_thread_cache.
# This may be replaced when dependencies are built.
