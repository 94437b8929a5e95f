!> Trace wrapper for the CalculiX comparison (tests/calculix): a UMAT that logs what the host passes
!> and what the real routine returns, at full precision, and changes nothing. CalculiX prints its .dat
!> with 7 digits only, too few for a 1e-8 comparison, so the test reads this log instead (and checks
!> that the .dat of the untraced executable agrees with it to its printed digits).
!>
!> build_ccx.sh renames the project's umat_ to camclay9_umat_ in a copy of camclay9_umat.o and links
!> this file in front of it. The log goes to $CAMCLAY9_TRACE (default umat_trace.txt). Not thread
!> safe: run the traced executable with OMP_NUM_THREADS=1.
!>
!> Log: a header line "# cmname=<CMNAME as received>|ndi nshr ntens nstatv nprops", a line
!> "# props" with PROPS, then one line per call:
!>   jstep(1:4) kinc noel npt  time(1:2) dtime pnewdt_in pnewdt_out  drot_is_identity  ddsdde_asym
!>   stran(ntens) dstran(ntens) stress_in(ntens) stress_out(ntens) statev_in(nstatv) statev_out(nstatv)
!> ddsdde_asym = max|D - D^T| / max|D| of the returned DDSDDE (before CalculiX symmetrises it).
!>
!> Compact binary log (for meshes of many elements, python/camclay9/calculix_mesh.py): when $CAMCLAY9_TRACE_BIN
!> names a file, the text log is not written; instead, per call, a stream record of 4 int32 (jstep(1),
!> kinc, noel, npt) and 12 + nstatv real64 (stran + dstran, stress_out, statev_out).
subroutine umat(stress, statev, ddsdde, sse, spd, scd, rpl, ddsddt, drplde, drpldt, &
                stran, dstran, time, dtime, temp, dtemp, predef, dpred, cmname, &
                ndi, nshr, ntens, nstatv, props, nprops, coords, drot, pnewdt, &
                celent, dfgrd0, dfgrd1, noel, npt, layer, kspt, jstep, kinc)
  use, intrinsic :: iso_fortran_env, only: real64, int32
  implicit none
  character(len=80), intent(in) :: cmname
  integer, intent(in) :: ndi, nshr, ntens, nstatv, nprops, noel, npt, layer, kspt, jstep(4), kinc
  real(real64), intent(inout) :: stress(ntens), statev(nstatv), sse, spd, scd, pnewdt
  real(real64), intent(out) :: ddsdde(ntens, ntens), rpl, ddsddt(ntens), drplde(ntens), drpldt
  real(real64), intent(in) :: stran(ntens), dstran(ntens), time(2), dtime, temp, dtemp, &
                              predef(*), dpred(*), props(nprops), coords(3), drot(3, 3), &
                              celent, dfgrd0(3, 3), dfgrd1(3, 3)
  interface
    subroutine camclay9_umat(stress, statev, ddsdde, sse, spd, scd, rpl, ddsddt, drplde, drpldt, &
                             stran, dstran, time, dtime, temp, dtemp, predef, dpred, cmname, &
                             ndi, nshr, ntens, nstatv, props, nprops, coords, drot, pnewdt, &
                             celent, dfgrd0, dfgrd1, noel, npt, layer, kspt, jstep, kinc)
      import :: real64
      character(len=80), intent(in) :: cmname
      integer, intent(in) :: ndi, nshr, ntens, nstatv, nprops, noel, npt, layer, kspt, jstep(4), kinc
      real(real64), intent(inout) :: stress(ntens), statev(nstatv), sse, spd, scd, pnewdt
      real(real64), intent(out) :: ddsdde(ntens, ntens), rpl, ddsddt(ntens), drplde(ntens), drpldt
      real(real64), intent(in) :: stran(ntens), dstran(ntens), time(2), dtime, temp, dtemp, &
                                  predef(*), dpred(*), props(nprops), coords(3), drot(3, 3), &
                                  celent, dfgrd0(3, 3), dfgrd1(3, 3)
    end subroutine camclay9_umat
  end interface
  integer, save :: unit
  logical, save :: opened = .false., binary = .false.   ! newunit= gives negative unit numbers
  character(len=512) :: path
  real(real64) :: stress_in(ntens), statev_in(nstatv), pnewdt_in, asym
  integer :: n, status
  logical :: identity

  if (.not. opened) then
    opened = .true.
    call get_environment_variable('CAMCLAY9_TRACE_BIN', path, n, status)
    binary = status == 0 .and. n > 0
    if (binary) then
      open (newunit=unit, file=trim(path), status='replace', action='write', access='stream', form='unformatted')
    else
      call get_environment_variable('CAMCLAY9_TRACE', path, n, status)
      if (status /= 0 .or. n == 0) path = 'umat_trace.txt'
      open (newunit=unit, file=trim(path), status='replace', action='write')
      write (unit, '(a,a,a,5(1x,i0))') '# cmname=', trim(cmname), '|', ndi, nshr, ntens, nstatv, nprops
      write (unit, '(a,*(1x,es24.16e3))') '# props', props
    end if
  end if
  stress_in = stress
  statev_in = statev
  pnewdt_in = pnewdt
  call camclay9_umat(stress, statev, ddsdde, sse, spd, scd, rpl, ddsddt, drplde, drpldt, &
                     stran, dstran, time, dtime, temp, dtemp, predef, dpred, cmname, &
                     ndi, nshr, ntens, nstatv, props, nprops, coords, drot, pnewdt, &
                     celent, dfgrd0, dfgrd1, noel, npt, layer, kspt, jstep, kinc)
  if (binary) then
    write (unit) int(jstep(1), int32), int(kinc, int32), int(noel, int32), int(npt, int32), &
      stran + dstran, stress, statev
    return
  end if
  identity = all(abs(drot - reshape([1, 0, 0, 0, 1, 0, 0, 0, 1], [3, 3])) == 0)
  asym = maxval(abs(ddsdde - transpose(ddsdde))) / max(maxval(abs(ddsdde)), tiny(1.0_real64))
  write (unit, '(7(i0,1x),5(es24.16e3,1x),l1,*(1x,es24.16e3))') jstep, kinc, noel, npt, time, dtime, &
    pnewdt_in, pnewdt, identity, asym, stran, dstran, stress_in, stress, statev_in, statev
  flush (unit)
end subroutine umat
